#include "io/image.h"

#include <png.h>

#include <cstring>

#include "io/atomic_file.h"
#include "io/input_check.h"

namespace lodline {

Status writePng(const std::filesystem::path& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<size_t>(image.width) * image.height * 4)
    return Error::runtime(path.string() + ": internal error: image buffer does not match its size");
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGBA;
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.rgba.data(), 0, nullptr))
    return Error::runtime(path.string() + ": PNG encoding failed: " + png.message);
  std::vector<uint8_t> bytes(size);
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.rgba.data(), 0, nullptr))
    return Error::runtime(path.string() + ": PNG encoding failed: " + png.message);
  return writeFileAtomically(path, [&](std::ostream& out) -> Status {
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(size));
    return {};
  });
}

Result<Image> readPng(const std::filesystem::path& path, uint64_t max_pixels) {
  if (Status s = checkInputFile(path, "PNG image"); !s) return s.error();
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    return Error::runtime(path.string() + ": cannot read PNG: " + png.message);
  png.format = PNG_FORMAT_RGBA;
  const uint64_t pixels = static_cast<uint64_t>(png.width) * png.height;
  if (pixels == 0) {
    png_image_free(&png);
    return Error::runtime(path.string() + ": PNG has no pixels");
  }
  if (pixels > max_pixels) {
    const std::string size = std::to_string(png.width) + "x" + std::to_string(png.height);
    png_image_free(&png);
    return Error::runtime(path.string() + ": PNG of " + size + " pixels is too large (at most " +
                          std::to_string(max_pixels) + " pixels here)");
  }
  Image image(static_cast<int>(png.width), static_cast<int>(png.height));
  if (!png_image_finish_read(&png, nullptr, image.rgba.data(), 0, nullptr))
    return Error::runtime(path.string() + ": cannot read PNG: " + png.message);
  return image;
}

}  // namespace lodline
