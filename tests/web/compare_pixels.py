"""Pixel agreement of two screenshots of the page in a box (tests/web/walkthrough.mjs): the same view
drawn twice (a link reopened, the downloaded PNG against the page, a model and its copy scaled by
1000) must agree pixel for pixel up to rasterisation's rounding.
Prints JSON: the share of pixels whose largest channel difference exceeds 24/255, the mean absolute
difference (0..1), the share of saturated (surface) pixels in A; exits 1 when the share exceeds MAX.
Usage: compare_pixels.py A.png B.png X0,Y0,X1,Y1 MAX_SHARE
"""
import json
import sys

import numpy as np
from PIL import Image


def main():
    a = np.asarray(Image.open(sys.argv[1]).convert('RGB'), dtype=np.int32)
    b = np.asarray(Image.open(sys.argv[2]).convert('RGB'), dtype=np.int32)
    x0, y0, x1, y1 = (int(v) for v in sys.argv[3].split(','))
    limit = float(sys.argv[4])
    if a.shape != b.shape:
        print(json.dumps({'error': f'sizes differ: {a.shape} vs {b.shape}'}))
        return 1
    a, b = a[y0:y1, x0:x1], b[y0:y1, x0:x1]
    difference = np.abs(a - b).max(axis=2)
    share = float((difference > 24).mean())
    saturated = float(((a.max(axis=2) - a.min(axis=2)) > 64).mean())
    print(json.dumps({'differing_share': round(share, 5), 'mean_difference': round(float(np.abs(a - b).mean()) / 255.0, 5),
                      'surface_share': round(saturated, 4)}))
    return 0 if share <= limit else 1


if __name__ == '__main__':
    sys.exit(main())
