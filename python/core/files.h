#pragma once
// Result's tubes, instancing points, strands, solid and files (files.cpp).

#include "result.h"

#include <optional>
#include <string>
#include <vector>

namespace dla::python {

py::tuple tubes(Result& result, std::optional<int> sides, std::optional<double> tolerance,
                std::optional<int> min_branch, std::optional<double> uv_scale);
py::tuple instances(Result& result);
py::tuple strands(Result& result);
py::tuple solid(Result& result, const py::dict& given);
void write(Result& result, const std::string& prefix, const std::vector<std::string>& formats);

}  // namespace dla::python
