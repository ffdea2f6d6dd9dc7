#!/usr/bin/python3
"""The denoiser's error split into bias and variance over renders with different seeds
(docs/denoising.md, "How the candidates were chosen").

    denoise_bias.py REF IMAGE...

IMAGE... are the same scene and spp denoised from renders with different seeds (bench/denoise_bias.sh
makes them). Per pixel and channel, in relative units (divided by ref^2 + 0.01, as relative MSE):
the variance over the images, and the bias^2 of their mean less the share of that variance the
mean still carries. Prints the mean relative MSE of the images, bias^2 and variance, then the
share of each on "edge" pixels: where the reference's brightness changes by more than 5 % to a
neighbour (dilated by one pixel). Needs Debian's python3-opencv, like denoise_metrics.py.
"""
import sys

import cv2
import numpy as np

from denoise_metrics import read


def main():
    if len(sys.argv) < 4:
        sys.exit("usage: denoise_bias.py REF IMAGE IMAGE...")
    ref = read(sys.argv[1])
    xs = np.array([read(p) for p in sys.argv[2:]])
    d = ref * ref + 0.01
    var = (xs.var(0, ddof=1) / d).mean(2)
    bias2 = ((xs.mean(0) - ref) ** 2 / d).mean(2) - var / len(xs)
    total = ((xs - ref) ** 2 / d).mean()
    lum = ref.mean(2)
    gx = np.abs(np.diff(lum, axis=1, append=lum[:, -1:]))
    gy = np.abs(np.diff(lum, axis=0, append=lum[-1:, :]))
    edge = cv2.dilate((np.maximum(gx, gy) / (lum + 0.1) > 0.05).astype(np.uint8), np.ones((3, 3), np.uint8)) > 0
    n = var.size
    print(f"relMSE {total:.6f} bias^2 {bias2.mean():.6f} variance {var.mean():.6f} | "
          f"edge pixels {edge.mean():.2f}: bias^2 {bias2[edge].sum() / n:.6f} variance {var[edge].sum() / n:.6f}")


if __name__ == "__main__":
    main()
