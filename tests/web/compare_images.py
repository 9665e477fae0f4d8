"""The web page's screenshot against the desktop `render` of the same view (tests/web/web_page.sh).

The two draw the same limit surface through different pipelines: the desktop tessellates on the GPU
per pixel size and evaluates K per fragment; the page draws the core's CPU tessellation (12 samples a
patch edge) with K interpolated from exact vertex values, with another font. Silhouettes and text
therefore move by a pixel or two, so a pixel-exact comparison would measure fonts and edges. What
must agree is what the picture says:
  1. the colour histogram: the share of each hue of the colour map among the surface's pixels
     (saturated pixels; background, text and grey UI are not), by histogram intersection;
  2. where the colours are: the mean colour of 40 x 40 pixel blocks holding surface, compared block
     by block (median of the mean |RGB| difference)
     robust to a pixel's shift, not to a wrong camera, colour range or scheme;
  3. how much surface there is (coverage of saturated pixels).
Prints the three numbers as JSON; exits 1 when one is outside its bound.
Usage: compare_images.py WEB.png DESKTOP.png
"""
import json
import sys

import numpy as np
from PIL import Image

HUE_BINS = 36
BLOCK = 40
MIN_INTERSECTION = 0.85   # share of surface pixels whose hue bin the other image also has
MAX_BLOCK_DIFFERENCE = 0.06  # median over surface blocks of the mean |RGB| difference (0..1)
MAX_COVERAGE_RATIO = 1.15    # larger coverage / smaller


def load(path):
    return np.asarray(Image.open(path).convert('RGB'), dtype=np.float64) / 255.0


def surface_hues(rgb):
    # Saturated pixels: the colour map's (the background and the UI are greys).
    high, low = rgb.max(axis=2), rgb.min(axis=2)
    saturated = (high - low) > 0.25
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    delta = np.where(high - low > 1e-9, high - low, 1.0)
    hue = np.where(high == r, ((g - b) / delta) % 6.0, np.where(high == g, (b - r) / delta + 2.0, (r - g) / delta + 4.0)) / 6.0
    return hue[saturated], saturated


def main():
    web, desktop = load(sys.argv[1]), load(sys.argv[2])
    if web.shape != desktop.shape:
        print(json.dumps({'error': f'sizes differ: {web.shape} vs {desktop.shape}'}))
        return 1
    web_hue, web_mask = surface_hues(web)
    desk_hue, desk_mask = surface_hues(desktop)
    web_hist = np.histogram(web_hue, bins=HUE_BINS, range=(0.0, 1.0))[0] / max(web_hue.size, 1)
    desk_hist = np.histogram(desk_hue, bins=HUE_BINS, range=(0.0, 1.0))[0] / max(desk_hue.size, 1)
    intersection = float(np.minimum(web_hist, desk_hist).sum())
    coverage = max(web_mask.sum(), desk_mask.sum()) / max(min(web_mask.sum(), desk_mask.sum()), 1)
    h, w = (web.shape[0] // BLOCK) * BLOCK, (web.shape[1] // BLOCK) * BLOCK
    blocks = lambda img: img[:h, :w].reshape(h // BLOCK, BLOCK, w // BLOCK, BLOCK, 3).mean(axis=(1, 3))
    # Over the blocks that hold surface in either image (the background would dilute it).
    holds = (blocks(np.repeat(web_mask[..., None], 3, axis=2)) + blocks(np.repeat(desk_mask[..., None], 3, axis=2)))[..., 0] > 0.1
    difference = np.abs(blocks(web) - blocks(desktop)).mean(axis=2)
    block_difference = float(np.median(difference[holds])) if holds.any() else 1.0
    result = {'hue_histogram_intersection': round(intersection, 4), 'median_block_difference': round(block_difference, 4),
              'coverage_ratio': round(float(coverage), 4), 'surface_pixels_web': int(web_mask.sum()),
              'surface_pixels_desktop': int(desk_mask.sum())}
    print(json.dumps(result))
    ok = intersection >= MIN_INTERSECTION and block_difference <= MAX_BLOCK_DIFFERENCE and coverage <= MAX_COVERAGE_RATIO
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
