#pragma once
//! \file input_file.h
//! A user's input file read within bounds: a regular file only, never a folder, a device or a
//! FIFO (which would block or never end), no more than it held when opened, and no larger than
//! the memory this machine has free. Every reader of a file a user names goes through here.

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace dla {

//! Throws InvalidInput unless `path` is a regular file or is not there (its reader's IOError
//! then says so): one line naming `option` as the front ends spell it (`leaf`), or the path
//! alone when `option` is empty.
void require_regular_file(const std::string& path, std::string_view option);

//! `path` opened to read, judged as require_regular_file judges it but by what was opened (a
//! FIFO put in its place in between cannot block), with its size then in `size`: a stream the
//! caller closes with std::fclose. Throws as read_input_file does, but for the size.
std::FILE* open_input_file(const std::string& path, std::string_view option, std::uint64_t& size);

//! The bytes of the regular file `path`, read to the size it had when opened. Throws
//! InvalidInput, naming `option`, for what require_regular_file refuses and for a file larger
//! than half the memory free; IOError for one that cannot be read.
std::string read_input_file(const std::string& path, std::string_view option);

}  // namespace dla
