// 16-bit PNG depth images (libpng) and their meshing.
#include "tools/io/depth_image.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <memory>
#include <string>

#include "format/output_file.h"

namespace meshvid {
namespace {

/// Deflate (PNG's compression) expands at most 1032-fold; rounded up for the filter bytes.
constexpr std::uint64_t kMaxDeflateExpansion = 1100;

/// Closes a FILE* on scope exit.
struct FileCloser {
  void operator()(std::FILE* file) const {
    if (file != nullptr) std::fclose(file);
  }
};
using UniqueFile = std::unique_ptr<std::FILE, FileCloser>;

/// Records libpng's error text and unwinds to the setjmp point.
void PngError(png_structp png, png_const_charp message) {
  auto* text = static_cast<std::string*>(png_get_error_ptr(png));
  if (text != nullptr) *text = message;
  png_longjmp(png, 1);
}

void PngWarning(png_structp, png_const_charp) {}

/// libpng write callback: appends to the std::string behind the io pointer.
void AppendToString(png_structp png, png_bytep data, png_size_t size) {
  auto* bytes = static_cast<std::string*>(png_get_io_ptr(png));
  bytes->append(reinterpret_cast<const char*>(data), size);
}

void FlushNothing(png_structp) {}

}  // namespace

Status WriteDepthPng(const std::string& path, const DepthImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.values.size() != static_cast<std::size_t>(image.width) * image.height) {
    return InvalidArgumentError(path + ": depth image is " + std::to_string(image.width) + " x " +
                                std::to_string(image.height) + " but holds " +
                                std::to_string(image.values.size()) + " values");
  }
  std::string encoded;
  std::string error;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, PngError, PngWarning);
  if (png == nullptr) return InternalError(path + ": libpng could not start");
  png_infop info = png_create_info_struct(png);
  // Big-endian rows, built before setjmp so no C++ object with a destructor is skipped.
  std::vector<png_byte> row(static_cast<std::size_t>(image.width) * 2);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return IoError(path + ": cannot write PNG: " + error);
  }
  png_set_write_fn(png, &encoded, AppendToString, FlushNothing);
  png_set_IHDR(png, info, image.width, image.height, 16, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const std::uint16_t value = image.at(u, v);
      row[2 * u] = static_cast<png_byte>(value >> 8);
      row[2 * u + 1] = static_cast<png_byte>(value & 0xff);
    }
    png_write_row(png, row.data());
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return WriteFileAtomically(path, encoded);
}

StatusOr<DepthImage> ReadDepthPng(const std::string& path) {
  UniqueFile file(std::fopen(path.c_str(), "rb"));
  if (!file) return NotFoundError(path + ": cannot open depth image");
  png_byte signature[8] = {};
  if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
    return CorruptError(path + ": not a PNG file");
  }
  // The file's size bounds the pixels it can hold (checked before they are allocated).
  // volatile: it lives across libpng's setjmp.
  const volatile std::uint64_t file_size = [&]() -> std::uint64_t {
    if (std::fseek(file.get(), 0, SEEK_END) != 0) return 0;
    const long end = std::ftell(file.get());
    return end > 0 ? static_cast<std::uint64_t>(end) : 0;
  }();
  if (std::fseek(file.get(), 8, SEEK_SET) != 0) return IoError(path + ": cannot seek");
  std::string error;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, PngError, PngWarning);
  if (png == nullptr) return InternalError(path + ": libpng could not start");
  png_infop info = png_create_info_struct(png);
  // Everything with a destructor lives outside the setjmp region's scope.
  DepthImage image;
  std::vector<png_byte> pixels;
  std::vector<png_bytep> rows;
  int bit_depth = 0;
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return CorruptError(path + ": damaged PNG: " + error);
  }
  png_init_io(png, file.get());
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  const int color_type = png_get_color_type(png, info);
  bit_depth = png_get_bit_depth(png, info);
  if (color_type != PNG_COLOR_TYPE_GRAY || (bit_depth != 16 && bit_depth != 8)) {
    png_destroy_read_struct(&png, &info, nullptr);
    return UnsupportedError(path +
                            ": depth images must be 16-bit greyscale PNG (this one has "
                            "colour type " +
                            std::to_string(color_type) + ", " + std::to_string(bit_depth) +
                            " bits)");
  }
  if (png_get_interlace_type(png, info) != PNG_INTERLACE_NONE) {
    png_set_interlace_handling(png);
  }
  png_read_update_info(png, info);
  image.width = static_cast<int>(png_get_image_width(png, info));
  image.height = static_cast<int>(png_get_image_height(png, info));
  const std::size_t row_bytes = png_get_rowbytes(png, info);
  const std::uint64_t pixel_bytes = std::uint64_t{row_bytes} * image.height;
  if (pixel_bytes / kMaxDeflateExpansion > file_size) {
    png_destroy_read_struct(&png, &info, nullptr);
    return CorruptError(path + ": a " + std::to_string(image.width) + " x " +
                        std::to_string(image.height) + " image needs " +
                        std::to_string(pixel_bytes) + " bytes, more than the " +
                        std::to_string(std::uint64_t{file_size}) +
                        "-byte file can hold (damaged header?)");
  }
  pixels.resize(row_bytes * image.height);
  rows.resize(image.height);
  for (int v = 0; v < image.height; ++v) rows[v] = pixels.data() + row_bytes * v;
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  image.values.resize(static_cast<std::size_t>(image.width) * image.height);
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      std::uint16_t value = 0;
      if (bit_depth == 16) {
        value = static_cast<std::uint16_t>((rows[v][2 * u] << 8) | rows[v][2 * u + 1]);
      } else {
        value = rows[v][u];
      }
      image.values[static_cast<std::size_t>(v) * image.width + u] = value;
    }
  }
  return image;
}

RangeGrid DepthImageToRangeGrid(const DepthImage& image, const PinholeIntrinsics& intrinsics,
                                double depth_scale) {
  RangeGrid grid;
  grid.width = image.width;
  grid.height = image.height;
  grid.points.resize(image.values.size(), Eigen::Vector3f::Zero());
  grid.depth.resize(image.values.size(), 0.0f);
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const std::uint16_t value = image.at(u, v);
      if (value == 0) continue;
      const double z = value * depth_scale;
      const std::size_t index = static_cast<std::size_t>(v) * image.width + u;
      grid.points[index] = (intrinsics.RayThrough(u, v) * z).cast<float>();
      grid.depth[index] = static_cast<float>(z);
    }
  }
  return grid;
}

StatusOr<TriangleMesh> MeshDepthImage(const DepthImage& image, const PinholeIntrinsics& intrinsics,
                                      double depth_scale,
                                      const Eigen::Isometry3d& world_from_camera,
                                      const RangeGridMeshing& meshing, const std::string& what) {
  if (image.width != intrinsics.width || image.height != intrinsics.height) {
    return InvalidArgumentError(what + ": depth image is " + std::to_string(image.width) + " x " +
                                std::to_string(image.height) + " pixels but its intrinsics say " +
                                std::to_string(intrinsics.width) + " x " +
                                std::to_string(intrinsics.height));
  }
  if (!(depth_scale > 0)) {
    return InvalidArgumentError(what + ": depth_scale must be > 0");
  }
  TriangleMesh mesh =
      TriangulateRangeGrid(DepthImageToRangeGrid(image, intrinsics, depth_scale), meshing);
  if (mesh.triangles.empty()) {
    return CorruptError(what +
                        ": depth image gives no triangle (no valid neighbouring "
                        "samples within the depth-jump ratio " +
                        std::to_string(meshing.max_depth_jump_ratio) + ")");
  }
  TransformMesh(Eigen::Affine3d(world_from_camera.matrix()), &mesh);
  MESHVID_RETURN_IF_ERROR(ValidateMesh(mesh, what));
  return mesh;
}

}  // namespace meshvid
