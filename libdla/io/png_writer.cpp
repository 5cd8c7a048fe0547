#include "dla/io/png_writer.h"

#include "output_file.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace dla {

namespace {

constexpr double kMaxSide = 8192;  // pixels: 200 MB of RGB at most
constexpr std::array<std::uint8_t, 3> kBackground = {0x38, 0x40, 0x4c};  // as the POV-Ray scene's
constexpr std::array<std::array<std::uint8_t, 3>, 3> kBands = {{{0xff, 0xff, 0xff}, {0x90, 0x90, 0x90}, {0, 0, 0}}};

//! Where the structure lies and how it is drawn: `scale` pixels a scene unit, dots `dot`
//! pixels wide.
struct Frame {
  Vec3 min = Vec3::Zero(), max = Vec3::Zero();
  double scale = 1.0, dot = 1.0;
  long long width = 0, height = 0;
};

Frame frame(const Cluster& cluster, const PngOptions& o) {
  Frame f;
  if (!cluster.particles.empty()) {
    f.min = f.max = cluster.particles.front().position;
    for (const Particle& p : cluster.particles) f.min = f.min.cwiseMin(p.position), f.max = f.max.cwiseMax(p.position);
  }
  // The dots' centres span the box and reach half a dot beyond. A structure too large for
  // the scale is drawn smaller, to fit kMaxSide pixels.
  const double extent = std::max(f.max.x() - f.min.x(), f.max.y() - f.min.y());
  const double room = kMaxSide - 2.0 * o.margin - o.pixels_per_spacing - 2.0;
  f.scale = std::min(o.pixels_per_spacing / cluster.spacing, extent > 0.0 ? room / extent : 1e300);
  f.dot = std::min(o.pixels_per_spacing, f.scale * cluster.spacing);
  const auto side = [&](double length) {
    return static_cast<long long>(std::ceil(length * f.scale + f.dot)) + 2LL * o.margin;
  };
  f.width = side(f.max.x() - f.min.x());
  f.height = side(f.max.y() - f.min.y());
  return f;
}

}  // namespace

std::pair<long long, long long> png_size(const Cluster& cluster, const PngOptions& options) {
  validate(options);
  const Frame f = frame(cluster, options);
  return {f.width, f.height};
}

void write_png(const Cluster& cluster, const std::string& path, const PngOptions& o) {
  validate(o);
  if (cluster.dimensions != 2) throw InvalidInput("a PNG draws 2D growth: this structure is 3D");
  const Frame f = frame(cluster, o);
  const auto width = static_cast<std::size_t>(f.width), height = static_cast<std::size_t>(f.height);
  std::vector<std::uint8_t> rgb(width * height * 3);
  for (std::size_t i = 0; i < rgb.size(); i += 3) std::copy(kBackground.begin(), kBackground.end(), rgb.begin() + static_cast<std::ptrdiff_t>(i));

  // Each particle a disk as wide as a dot (at least a pixel), later ones over earlier.
  const double radius = std::max(0.5, 0.5 * f.dot), offset = o.margin + 0.5 * f.dot, scale = f.scale;
  const std::size_t count = cluster.particles.size();
  // Which band: the attach order runs through the cycle `bands` times.
  const auto band = [&](std::size_t i) -> const std::array<std::uint8_t, 3>& {
    return kBands[static_cast<std::size_t>(static_cast<double>(i) / static_cast<double>(count) * o.bands * 3.0) % 3];
  };
  const auto dot = [&](const Vec3& p, const std::array<std::uint8_t, 3>& color) {
    const double cx = offset + (p.x() - f.min.x()) * scale;
    const double cy = static_cast<double>(height) - (offset + (p.y() - f.min.y()) * scale);  // y up
    const auto x0 = static_cast<long long>(std::floor(cx - radius)), x1 = static_cast<long long>(std::ceil(cx + radius));
    const auto y0 = static_cast<long long>(std::floor(cy - radius)), y1 = static_cast<long long>(std::ceil(cy + radius));
    for (long long y = std::max(0LL, y0); y < std::min(f.height, y1); ++y)
      for (long long x = std::max(0LL, x0); x < std::min(f.width, x1); ++x) {
        const double dx = static_cast<double>(x) + 0.5 - cx, dy = static_cast<double>(y) + 0.5 - cy;
        // A dot narrower than a pixel still takes the pixel it falls in.
        if (dx * dx + dy * dy > radius * radius && !(x == static_cast<long long>(cx) && y == static_cast<long long>(cy)))
          continue;
        std::copy(color.begin(), color.end(), rgb.begin() + static_cast<std::ptrdiff_t>((static_cast<std::size_t>(y) * width + static_cast<std::size_t>(x)) * 3));
      }
  };
  for (std::size_t i = 0; i < count; ++i) dot(cluster.particles[i].position, band(i));
  // A link: dots half a dot apart, in its later particle's band.
  for (const Link& link : cluster.links) {
    const Vec3& a = cluster.particles[static_cast<std::size_t>(link.earlier)].position;
    const Vec3& b = cluster.particles[static_cast<std::size_t>(link.later)].position;
    const auto steps = static_cast<std::size_t>(std::ceil((b - a).norm() * scale / std::max(0.5, 0.5 * f.dot)));
    for (std::size_t k = 1; k < steps; ++k)
      dot(a + (b - a) * (static_cast<double>(k) / static_cast<double>(steps)), band(static_cast<std::size_t>(link.later)));
  }

  detail::throw_if_stopped("drawing ", path);  // before libpng, whose errors jump past C++ frames
  // libpng reports its errors by longjmp, past any C++ frame: it writes into memory here,
  // and the file is written after.
  std::string encoded;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw IOError(path + ": libpng could not start");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw IOError(path + ": libpng could not encode the picture");
  }
  png_set_write_fn(
      png, &encoded,
      [](png_structp p, png_bytep data, png_size_t length) {
        static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<const char*>(data), length);
      },
      nullptr);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (std::size_t y = 0; y < height; ++y) png_write_row(png, rgb.data() + y * width * 3);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);

  detail::OutputFile out(path);
  out << encoded;
  out.commit();
}

}  // namespace dla
