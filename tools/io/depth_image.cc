// 16-bit PNG depth images and 8-bit colour images beside them (libpng), and their meshing.
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

/// Encodes `rows` (height rows of row_bytes, as PNG stores them) as a PNG of `colour_type`
/// and `bit_depth`, written atomically to `path`.
Status EncodePng(const std::string& path, int width, int height, int bit_depth, int colour_type,
                 const std::vector<png_byte>& pixels) {
  std::string encoded;
  std::string error;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, PngError, PngWarning);
  if (png == nullptr) return InternalError(path + ": libpng could not start");
  png_infop info = png_create_info_struct(png);
  const std::size_t row_bytes = pixels.size() / static_cast<std::size_t>(height);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return IoError(path + ": cannot write PNG: " + error);
  }
  png_set_write_fn(png, &encoded, AppendToString, FlushNothing);
  png_set_IHDR(png, info, width, height, bit_depth, colour_type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int v = 0; v < height; ++v) {
    png_write_row(png, const_cast<png_bytep>(pixels.data() + row_bytes * v));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return WriteFileAtomically(path, encoded);
}

}  // namespace

Status WriteDepthPng(const std::string& path, const DepthImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.values.size() != static_cast<std::size_t>(image.width) * image.height) {
    return InvalidArgumentError(path + ": depth image is " + std::to_string(image.width) + " x " +
                                std::to_string(image.height) + " but holds " +
                                std::to_string(image.values.size()) + " values");
  }
  // Big-endian samples, as PNG stores 16 bits.
  std::vector<png_byte> pixels(image.values.size() * 2);
  for (std::size_t i = 0; i < image.values.size(); ++i) {
    pixels[2 * i] = static_cast<png_byte>(image.values[i] >> 8);
    pixels[2 * i + 1] = static_cast<png_byte>(image.values[i] & 0xff);
  }
  return EncodePng(path, image.width, image.height, 16, PNG_COLOR_TYPE_GRAY, pixels);
}

Status WriteColourPng(const std::string& path, const ColourImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height) {
    return InvalidArgumentError(path + ": colour image is " + std::to_string(image.width) + " x " +
                                std::to_string(image.height) + " but holds " +
                                std::to_string(image.pixels.size()) + " pixels");
  }
  std::vector<png_byte> pixels(image.pixels.size() * 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) pixels[3 * i + c] = image.pixels[i][c];
  }
  return EncodePng(path, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, pixels);
}

namespace {

/// A PNG's pixels as libpng gives them after the transforms its reader set.
struct DecodedPng {
  int width = 0;
  int height = 0;
  int bit_depth = 0;  ///< of a channel, after the transforms
  std::size_t row_bytes = 0;
  std::vector<png_byte> pixels;

  const png_byte* row(int v) const { return pixels.data() + row_bytes * v; }
};

/// Decides, from a PNG's colour type and bit depth, whether it is read and with which
/// transforms: an error (naming the file) refuses it.
using PngPreparer = Status (*)(png_structp png, int colour_type, int bit_depth,
                               const std::string& path);

/// Reads the PNG at `path` (`kind` names it in messages: "depth image", "colour image").
StatusOr<DecodedPng> DecodePng(const std::string& path, const char* kind, PngPreparer prepare) {
  UniqueFile file(std::fopen(path.c_str(), "rb"));
  if (!file) return NotFoundError(path + ": cannot open " + kind);
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
  DecodedPng image;
  Status refused;
  std::vector<png_bytep> rows;
  std::size_t stored_row_bytes = 0;
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return CorruptError(path + ": damaged PNG: " + error);
  }
  png_init_io(png, file.get());
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  // The bound on what the file can hold uses the rows as stored, before any expansion.
  stored_row_bytes = png_get_rowbytes(png, info);
  refused = prepare(png, png_get_color_type(png, info), png_get_bit_depth(png, info), path);
  if (!refused.ok()) {
    png_destroy_read_struct(&png, &info, nullptr);
    return refused;
  }
  if (png_get_interlace_type(png, info) != PNG_INTERLACE_NONE) {
    png_set_interlace_handling(png);
  }
  png_read_update_info(png, info);
  image.width = static_cast<int>(png_get_image_width(png, info));
  image.height = static_cast<int>(png_get_image_height(png, info));
  image.bit_depth = png_get_bit_depth(png, info);
  image.row_bytes = png_get_rowbytes(png, info);
  const std::uint64_t pixel_bytes = std::uint64_t{stored_row_bytes} * image.height;
  if (pixel_bytes / kMaxDeflateExpansion > file_size) {
    png_destroy_read_struct(&png, &info, nullptr);
    return CorruptError(path + ": a " + std::to_string(image.width) + " x " +
                        std::to_string(image.height) + " image needs " +
                        std::to_string(pixel_bytes) + " bytes, more than the " +
                        std::to_string(std::uint64_t{file_size}) +
                        "-byte file can hold (damaged header?)");
  }
  image.pixels.resize(image.row_bytes * image.height);
  rows.resize(image.height);
  for (int v = 0; v < image.height; ++v) rows[v] = image.pixels.data() + image.row_bytes * v;
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return image;
}

/// Depth images: 8- or 16-bit greyscale, read as they are (16-bit rows big-endian).
Status PrepareDepth(png_structp, int colour_type, int bit_depth, const std::string& path) {
  if (colour_type != PNG_COLOR_TYPE_GRAY || (bit_depth != 16 && bit_depth != 8)) {
    return UnsupportedError(path +
                            ": depth images must be 16-bit greyscale PNG (this one has "
                            "colour type " +
                            std::to_string(colour_type) + ", " + std::to_string(bit_depth) +
                            " bits)");
  }
  return Status::Ok();
}

/// Colour images: any PNG, read as 8-bit RGB (palettes expanded, grey copied to the three
/// channels, 16 bits reduced to 8, alpha dropped).
Status PrepareColour(png_structp png, int colour_type, int bit_depth, const std::string&) {
  if (colour_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (bit_depth == 16) png_set_strip_16(png);
  if (colour_type & PNG_COLOR_MASK_ALPHA) png_set_strip_alpha(png);
  if (colour_type == PNG_COLOR_TYPE_GRAY || colour_type == PNG_COLOR_TYPE_GRAY_ALPHA) {
    png_set_gray_to_rgb(png);
  }
  return Status::Ok();
}

}  // namespace

StatusOr<DepthImage> ReadDepthPng(const std::string& path) {
  MESHVID_ASSIGN_OR_RETURN(const DecodedPng png, DecodePng(path, "depth image", PrepareDepth));
  const bool sixteen = png.bit_depth == 16;
  DepthImage image;
  image.width = png.width;
  image.height = png.height;
  image.values.resize(static_cast<std::size_t>(image.width) * image.height);
  for (int v = 0; v < image.height; ++v) {
    const png_byte* row = png.row(v);
    for (int u = 0; u < image.width; ++u) {
      const std::uint16_t value =
          sixteen ? static_cast<std::uint16_t>((row[2 * u] << 8) | row[2 * u + 1]) : row[u];
      image.values[static_cast<std::size_t>(v) * image.width + u] = value;
    }
  }
  return image;
}

StatusOr<ColourImage> ReadColourPng(const std::string& path) {
  MESHVID_ASSIGN_OR_RETURN(const DecodedPng png, DecodePng(path, "colour image", PrepareColour));
  ColourImage image;
  image.width = png.width;
  image.height = png.height;
  image.pixels.resize(static_cast<std::size_t>(image.width) * image.height);
  for (int v = 0; v < image.height; ++v) {
    const png_byte* row = png.row(v);
    for (int u = 0; u < image.width; ++u) {
      image.pixels[static_cast<std::size_t>(v) * image.width + u] =
          Colour(row[3 * u], row[3 * u + 1], row[3 * u + 2]);
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
                                      const RangeGridMeshing& meshing, const std::string& what,
                                      const ColourImage* colour, const std::string& colour_what) {
  if (image.width != intrinsics.width || image.height != intrinsics.height) {
    return InvalidArgumentError(what + ": depth image is " + std::to_string(image.width) + " x " +
                                std::to_string(image.height) + " pixels but its intrinsics say " +
                                std::to_string(intrinsics.width) + " x " +
                                std::to_string(intrinsics.height));
  }
  if (!(depth_scale > 0)) {
    return InvalidArgumentError(what + ": depth_scale must be > 0");
  }
  RangeGrid grid = DepthImageToRangeGrid(image, intrinsics, depth_scale);
  if (colour != nullptr) {
    if (colour->width != image.width || colour->height != image.height) {
      return InvalidArgumentError(
          colour_what + ": colour image is " + std::to_string(colour->width) + " x " +
          std::to_string(colour->height) + " pixels but its depth image " + what + " is " +
          std::to_string(image.width) + " x " + std::to_string(image.height));
    }
    grid.colours = colour->pixels;
  }
  TriangleMesh mesh = TriangulateRangeGrid(grid, meshing);
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
