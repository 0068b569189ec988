#pragma once
// How close a predicted image is to a photograph, as `btflut eval` reports it: in
// distribution (masked 64-bin grey histograms: L1 and earth mover's distance) and in place
// (RGB PSNR and grey SSIM over the mask).
//
//   ImageErrors e = compareImages(predicted, photo, mask);   // e.l1, e.emd, e.psnr, e.ssim
//
// Both images are first quantised to the photo's bit depth, as a saved prediction would be.
// A grey prediction of a colour photo is compared as grey in every channel.

#include <cmath>
#include <vector>

#include "core/image/image.h"

namespace btflut {

struct ImageErrors {
    double l1 = 0;    ///< sum of |h_pred - h_photo| over 64 grey bins, in [0, 2]
    double emd = 0;   ///< earth mover's distance of the two histograms, grey scale units [0, 1]
    double psnr = 0;  ///< 10 log10(1 / MSE) over the mask's pixels and the photo's channels, dB (capped at 99)
    double ssim = 0;  ///< mean structural similarity of the grey images over the mask (Gaussian window, sigma 1.5)
    double maxDifference = 0;   ///< largest |difference| of a sample over the mask, value units [0, 1]
    double meanDifference = 0;  ///< mean |difference| over the mask's pixels and the photo's channels
};

/// The errors of `predicted` against `photo` (same size; mask of that size).
ImageErrors compareImages(const Image& predicted, const Image& photo, const Mask& mask);

/// The same from the images' codes (`predicted` brought to the photo's bit depth first).
ImageErrors compareCodes(const ImageCodes& predicted, const ImageCodes& photo, const Mask& mask);

/// The histogram L1 of a target distribution against the photo, as compareImages measures a
/// prediction's: a mixture of quantile functions (values 0..1, evenly spaced probabilities;
/// `weights` their shares, e.g. regions' texel counts) binned into the photo's 64 grey bins
/// (each value at the nearest code of the photo's grey), against the photo's masked grey
/// histogram. How far the estimate of the histogram at a light is from the truth, apart from
/// how well a prediction was matched to it.
double targetL1(const std::vector<std::vector<float>>& quantiles, const std::vector<double>& weights,
                const Image& photo, const Mask& mask);

/// How two methods' figures on the same items (images, lights) differ: the mean of the
/// per-item differences a - b and its standard error; both NaN when the lists differ in
/// length, are empty, or hold a NaN.
struct PairedDifference {
    double mean = NAN, standardError = NAN;
};
PairedDifference pairedDifference(const std::vector<double>& a, const std::vector<double>& b);

/// Where a prediction misses, for the eyes: each pixel's mean |difference| over the photo's
/// channels (a grey prediction broadcast), times `gain`, on a hot scale (black 0, red, yellow,
/// white at 1 / gain and above); pixels outside the mask light grey. Same sizes as compareImages.
Image errorMap(const Image& predicted, const Image& photo, const Mask& mask, float gain);

/// The image quantised to integer codes of `bitDepth` bits (values as code / max code).
Image quantised(const Image& image, int bitDepth);

}  // namespace btflut
