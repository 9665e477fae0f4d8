#include "pipeline/indexed_png.h"

#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "core/mesh/atomic_file.h"

// stb_image_write's deflate (in libstb, declared only inside its implementation part); the result
// is malloc'ed.
extern "C" unsigned char* stbi_zlib_compress(unsigned char* data, int dataLength, int* outLength, int quality);

namespace polarview {
namespace {

struct ColourCount {
  std::array<uint8_t, 3> rgb;
  uint64_t count;
};

uint32_t packRgb(const uint8_t* p) { return uint32_t(p[0]) << 16 | uint32_t(p[1]) << 8 | p[2]; }

// A box of colours (a range of `colours`) and the channel it spreads most along.
struct Box {
  size_t begin, end;
  int channel = 0, spread = 0;
};

void measure(Box& box, const std::vector<ColourCount>& colours) {
  std::array<int, 3> lo{255, 255, 255}, hi{0, 0, 0};
  for (size_t i = box.begin; i < box.end; ++i)
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min<int>(lo[c], colours[i].rgb[c]);
      hi[c] = std::max<int>(hi[c], colours[i].rgb[c]);
    }
  box.spread = -1;
  for (int c = 0; c < 3; ++c)
    if (hi[c] - lo[c] > box.spread) box.spread = hi[c] - lo[c], box.channel = c;
}

// Median cut: splits the widest box at the pixel-weighted median of its widest channel until there
// are `size` boxes (or no box has two colours); the palette is each box's weighted mean.
std::vector<std::array<uint8_t, 3>> medianCut(std::vector<ColourCount>& colours, size_t size) {
  std::vector<Box> boxes{{0, colours.size()}};
  measure(boxes[0], colours);
  while (boxes.size() < size) {
    auto widest = std::max_element(boxes.begin(), boxes.end(), [](const Box& a, const Box& b) { return a.spread < b.spread; });
    if (widest->spread <= 0) break;
    Box box = *widest;
    std::sort(colours.begin() + long(box.begin), colours.begin() + long(box.end),
              [c = box.channel](const ColourCount& a, const ColourCount& b) { return a.rgb[c] < b.rgb[c]; });
    uint64_t total = 0, running = 0;
    for (size_t i = box.begin; i < box.end; ++i) total += colours[i].count;
    size_t split = box.begin + 1;
    for (size_t i = box.begin; i + 1 < box.end; ++i) {
      running += colours[i].count;
      split = i + 1;
      if (2 * running >= total) break;
    }
    Box low{box.begin, split}, high{split, box.end};
    measure(low, colours);
    measure(high, colours);
    *widest = low;
    boxes.push_back(high);
  }
  std::vector<std::array<uint8_t, 3>> palette;
  for (const Box& box : boxes) {
    std::array<double, 3> sum{0, 0, 0};
    double weight = 0;
    for (size_t i = box.begin; i < box.end; ++i) {
      for (int c = 0; c < 3; ++c) sum[c] += double(colours[i].rgb[c]) * double(colours[i].count);
      weight += double(colours[i].count);
    }
    std::array<uint8_t, 3> mean;
    for (int c = 0; c < 3; ++c) mean[c] = uint8_t(std::clamp(sum[c] / weight + 0.5, 0.0, 255.0));
    palette.push_back(mean);
  }
  return palette;
}

uint32_t crc32(const std::string& bytes, size_t from) {
  uint32_t crc = 0xFFFFFFFFu;
  for (size_t i = from; i < bytes.size(); ++i) {
    crc ^= uint8_t(bytes[i]);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void appendBigEndian(std::string& out, uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(char((value >> shift) & 0xFF));
}

void appendChunk(std::string& png, const char* type, const std::string& body) {
  appendBigEndian(png, uint32_t(body.size()));
  const size_t start = png.size();
  png.append(type, 4);
  png += body;
  appendBigEndian(png, crc32(png, start));
}

}  // namespace

void writeIndexedPngAtomic(const std::string& path, const RgbaImage& image) {
  if (image.width <= 0 || image.height <= 0 || image.pixels.size() != size_t(image.width) * image.height * 4)
    throw std::runtime_error("writeIndexedPngAtomic: empty or inconsistent image for " + path);
  const size_t pixelCount = size_t(image.width) * size_t(image.height);

  // The colours and their pixel counts, then the palette and each colour's entry in it.
  std::unordered_map<uint32_t, uint64_t> counts;
  for (size_t i = 0; i < pixelCount; ++i) ++counts[packRgb(&image.pixels[4 * i])];
  std::vector<ColourCount> colours;
  colours.reserve(counts.size());
  for (const auto& [rgb, count] : counts) colours.push_back({{uint8_t(rgb >> 16), uint8_t(rgb >> 8), uint8_t(rgb)}, count});
  std::vector<std::array<uint8_t, 3>> palette = medianCut(colours, 256);
  std::unordered_map<uint32_t, uint8_t> entry;
  for (const auto& [rgb, count] : counts) {
    const int r = int(rgb >> 16), g = int((rgb >> 8) & 0xFF), b = int(rgb & 0xFF);
    int best = 0, bestDistance = 1 << 30;
    for (size_t k = 0; k < palette.size(); ++k) {
      const int dr = r - palette[k][0], dg = g - palette[k][1], db = b - palette[k][2];
      const int d = dr * dr + dg * dg + db * db;
      if (d < bestDistance) bestDistance = d, best = int(k);
    }
    entry[rgb] = uint8_t(best);
  }

  // Rows of filter byte 0 (none: best for palette indices) and indices, deflated by stb.
  std::vector<uint8_t> rows;
  rows.reserve(pixelCount + size_t(image.height));
  for (int y = 0; y < image.height; ++y) {
    rows.push_back(0);
    for (int x = 0; x < image.width; ++x) rows.push_back(entry[packRgb(image.at(x, y))]);
  }
  int deflatedSize = 0;
  unsigned char* deflated = stbi_zlib_compress(rows.data(), int(rows.size()), &deflatedSize, 9);
  if (!deflated) throw std::runtime_error(path + ": cannot compress the PNG");
  const std::string idat(reinterpret_cast<const char*>(deflated), size_t(deflatedSize));
  std::free(deflated);

  std::string png("\x89PNG\r\n\x1a\n", 8), header, plte;
  appendBigEndian(header, uint32_t(image.width));
  appendBigEndian(header, uint32_t(image.height));
  header += std::string("\x08\x03\x00\x00\x00", 5);  // 8 bits, indexed colour, deflate, filter 0, no interlace
  for (const auto& c : palette) plte.append(reinterpret_cast<const char*>(c.data()), 3);
  appendChunk(png, "IHDR", header);
  appendChunk(png, "PLTE", plte);
  appendChunk(png, "IDAT", idat);
  appendChunk(png, "IEND", "");
  writeFileAtomically(path, png);
}

}  // namespace polarview
