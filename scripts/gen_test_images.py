#!/usr/bin/env python3
"""Writes tests/data/images/blocks.jpg: a 16 × 8 JPEG (quality 100, no chroma subsampling) of
two flat 8 × 8 blocks, sRGB (200, 60, 30) on the left and (20, 90, 220) on the right, with
OpenImageIO's JPEG encoder. tests/image_io.rs reads it back against those values (JPEG keeps a
flat 8 × 8 block within a code value or two).

Usage: pip install OpenImageIO; python3 scripts/gen_test_images.py
"""
import os

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
out = os.path.join(ROOT, "tests", "data", "images", "blocks.jpg")
img = np.zeros((8, 16, 3), dtype=np.uint8)
img[:, :8] = (200, 60, 30)
img[:, 8:] = (20, 90, 220)
spec = oiio.ImageSpec(16, 8, 3, "uint8")
spec.attribute("Compression", "jpeg:100")
spec.attribute("jpeg:subsampling", "4:4:4")
o = oiio.ImageOutput.create(out)
o.open(out, spec)
o.write_image(img)
o.close()
print("wrote", out)
