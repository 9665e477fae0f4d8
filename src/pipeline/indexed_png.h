// Small PNGs for shipped images (the figure gallery): the image reduced to a palette of at most 256
// colours by median cut and written as an 8-bit indexed PNG, about a third of the RGBA file's size.
#pragma once

#include <string>

#include "pipeline/image.h"

namespace polarview {

// Writes `image` (opaque: alpha is dropped) as an indexed PNG, atomically as writePngAtomic does.
// Images of at most 256 colours are exact; others get the palette of Heckbert's median cut over
// their colours weighted by pixel count, each colour mapped to its nearest palette entry (no
// dithering: flat areas stay flat and compress). Throws as writePngAtomic. [O(pixels + colours * 256)]
void writeIndexedPngAtomic(const std::string& path, const RgbaImage& image);

}  // namespace polarview
