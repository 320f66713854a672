// Fuzz target: detail-map PNGs (`--detail-map FILE.png`), read with the detail-map pixel
// limit and turned into per-pixel factors of T as src/app/model.cpp does.
#include <cmath>

#include "harness.h"
#include "io/image.h"

LODLINE_FUZZ_TARGET(detail_map_png) {
  using namespace lodline;
  const fuzz::InputFile input(".png", "", data, size);
  Result<Image> image = readPng(input.path(), kMaxDetailMapPixels);
  if (!image) {
    fuzz::expectCleanError(image.error(), input.path());
    return;
  }
  if (image->width <= 0 || image->height <= 0 ||
      static_cast<uint64_t>(image->width) * static_cast<uint64_t>(image->height) > kMaxDetailMapPixels ||
      image->rgba.size() != static_cast<size_t>(image->width) * image->height * 4)
    fuzz::fail("readPng returned an image of inconsistent size");
  double sum = 0.0;
  for (size_t i = 0; i < image->rgba.size(); i += 4) {
    const uint8_t* px = &image->rgba[i];
    sum += (0.299f * px[0] + 0.587f * px[1] + 0.114f * px[2]) / 255.0f;
  }
  if (!std::isfinite(sum)) fuzz::fail("non-finite detail map");
}
