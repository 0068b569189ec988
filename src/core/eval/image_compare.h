#pragma once
// The figures of `btflut compare` (screenshot tests): two images' errors under a mask (PSNR,
// SSIM, max, mean, histogram L1 and EMD from metrics.h; the 99th percentile of the samples'
// differences; the share of pixels past a threshold; alpha's), the bounds a tolerance sets on
// them, and the pictures of where two images differ.
//
//   CompareFigures f;
//   alphaFigures(a, b, mask, threshold, f);   // before makeComparable drops alpha
//   makeComparable(a, b);                     // grey against RGB: compared as RGB
//   differenceFigures(a, b, mask, threshold, f);
//   for (const Bound& bound : tolerance.bounds) if (!within(f, bound)) ...

#include <string>
#include <vector>

#include "core/eval/metrics.h"
#include "core/image/image.h"

namespace btflut {

// A bound on one figure: psnr and ssim from below, the rest from above; max, mean and p99 in
// 1/255, pixels in per cent. `threshold` is no bound: the difference (1/255) beyond which a
// pixel counts in `pixels`.
struct Bound {
    std::string name;
    double limit = 0;
};

struct Tolerance {
    std::vector<Bound> bounds;
    double threshold = 0;
};

// The errors; the 99th percentile of the samples' absolute difference over the mask (1/255),
// a bound that lets a few samples be far off, as two renderers that round a value differently
// leave them where a LUT is steep; and the share of pixels (per cent) whose largest channel
// difference exceeds the threshold, as pixelmatch and ImageMagick's `compare -metric AE -fuzz`
// count them.
struct CompareFigures {
    ImageErrors e;
    double p99 = 0;
    double pixels = 0;
    // The alpha channel's largest difference (1/255; opaque where a file keeps no alpha) and
    // the share of pixels (per cent) where it exceeds the threshold: a pixel made transparent
    // is another image, whatever its colour.
    bool alpha = false;  // either image keeps one
    double alphaMax = 0, alphaPixels = 0;
    bool identical() const { return e.maxDifference == 0 && alphaMax == 0; }
};

/// Its figure by name (psnr, ssim, max, mean, p99, pixels, l1, emd).
double figure(const CompareFigures& f, const std::string& name);
/// Whether a figure keeps its bound (psnr and ssim from below, the rest from above).
bool within(const CompareFigures& f, const Bound& b);
/// The alpha figures (`threshold` in 1/255), if either image keeps alpha; mask-wide.
void alphaFigures(const ImageCodes& a, const ImageCodes& b, const Mask& mask, double threshold, CompareFigures& f);
/// Whether alpha differs by no more than the tolerance's max (its threshold when it sets none).
bool alphaWithin(const CompareFigures& f, const Tolerance& t);
/// A grey image against an RGB one: the grey in all three channels, so both compare as RGB.
void makeComparable(ImageCodes& a, ImageCodes& b);
/// The errors, p99 and pixels of two comparable images of one size (another bit depth is
/// recoded as compareCodes does).
void differenceFigures(const ImageCodes& a, const ImageCodes& b, const Mask& mask, double threshold, CompareFigures& f);
/// The part of `image` in the rectangle (x, y, width, height), x right and y down from the
/// top left (the caller checks that it fits).
ImageCodes cropped(const ImageCodes& image, int x, int y, int width, int height);
/// Where the images differ: the expected image dimmed, each differing pixel red by its largest
/// channel difference (`full` /255 and more: full red; any difference at least a quarter),
/// outside the mask dark blue.
Image differenceImage(const Image& a, const Image& b, const Mask& mask, double full);
/// Expected | actual | difference, side by side, RGB, under a strip that names each pane.
Image sideBySide(const Image& actual, const Image& expected, const Image& difference);

}  // namespace btflut
