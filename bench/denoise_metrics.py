#!/usr/bin/python3
"""SSIM and a classical baseline for bench/denoise.sh (docs/denoising.md, "Measured").

    denoise_metrics.py REF RAW DENOISED

Prints one line: the SSIM of RAW and of DENOISED against REF, then OpenCV's non-local means
(fastNlMeansDenoisingColored) applied to RAW: its relative MSE, its SSIM, its seconds and the
filter strength h used. Needs Debian's python3-opencv (GLINT_BENCH_DEPS=1 scripts/install-deps.sh)
and runs under the system Python (/usr/bin/python3), where Debian installs cv2.

SSIM (Wang et al. 2004: Gaussian window of sigma 1.5, K1 = 0.01, K2 = 0.03) is computed per
channel on the display image: linear values clamped to [0, 1] and sRGB-encoded, as a viewer sees
them; the mean over pixels and channels.

OpenCV's filter works on 8-bit images: RAW is sRGB-encoded after dividing by a white point (the
99.5th percentile, at least 1), filtered, decoded and scaled back; pixels brighter than the white
point keep RAW's values (the lamp). h is the best of several strengths measured against REF: an
oracle no user has, which favours the baseline.
"""
import os
import sys
import time

os.environ.setdefault("OPENCV_IO_ENABLE_OPENEXR", "1")
import cv2  # noqa: E402
import numpy as np  # noqa: E402


def read(path):
    img = cv2.imread(path, cv2.IMREAD_UNCHANGED)
    if img is None:
        sys.exit(f"denoise_metrics: cannot read {path}")
    return img[:, :, :3].astype(np.float64)  # B, G, R: the order does not matter here


def encode(x):
    x = np.clip(x, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def decode(v):
    return np.where(v <= 0.04045, v / 12.92, np.power((v + 0.055) / 1.055, 2.4))


def ssim(x, ref):
    a, b = encode(x), encode(ref)
    c1, c2 = 0.01**2, 0.03**2
    blur = lambda m: cv2.GaussianBlur(m, (11, 11), 1.5)  # noqa: E731
    mu_a, mu_b = blur(a), blur(b)
    var_a = blur(a * a) - mu_a * mu_a
    var_b = blur(b * b) - mu_b * mu_b
    cov = blur(a * b) - mu_a * mu_b
    s = ((2 * mu_a * mu_b + c1) * (2 * cov + c2)) / ((mu_a**2 + mu_b**2 + c1) * (var_a + var_b + c2))
    return float(s.mean())


def rel_mse(x, ref):
    return float(np.mean((x - ref) ** 2 / (ref * ref + 0.01)))


def opencv_nlmeans(raw, h):
    white = max(1.0, float(np.percentile(raw, 99.5)))
    img8 = np.round(encode(raw / white) * 255).astype(np.uint8)
    start = time.perf_counter()
    out8 = cv2.fastNlMeansDenoisingColored(img8, None, h, h, 7, 21)
    seconds = time.perf_counter() - start
    out = decode(out8.astype(np.float64) / 255) * white
    out = np.where(raw > white, raw, out)
    return out, seconds


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: denoise_metrics.py REF RAW DENOISED")
    ref, raw, den = (read(p) for p in sys.argv[1:])
    best = None
    for h in (2, 3, 5, 8, 12, 18):
        out, seconds = opencv_nlmeans(raw, h)
        e = rel_mse(out, ref)
        if best is None or e < best[0]:
            best = (e, out, seconds, h)
    e, out, seconds, h = best
    print(f"{ssim(raw, ref):.4f} {ssim(den, ref):.4f} {e:.6f} {ssim(out, ref):.4f} {seconds:.2f} {h}")


if __name__ == "__main__":
    main()
