#pragma once
// The .rti file of RTI tools for hemispherical harmonics (Cultural Heritage Imaging's HSH
// format, which RTIViewer and RTIBuilder read and write), so an HSH light model opens there:
//
//   #HSH1.2\n (comments)  3\n  WIDTH HEIGHT 3\n  TERMS 2 1\n
//   then TERMS float32 scales and TERMS float32 biases (little-endian),
//   then per pixel, rows top first, per band R, G, B, per term: one byte.
//
// A coefficient is byte / 255 * scale + bias, and a band's value at a light is the sum of its
// coefficients times the HSH basis there (light_model.cpp's basisTerms: the same functions and
// order), 0..1. btflut's model (one luminance channel, times its LRGB albedo) is written per
// band: coefficient = albedo_c / 255 * the plane's value, requantised per term over every
// pixel and band (at most half a code of the file's own step).

#include "core/io/file_io.h"
#include "core/predict/light_model.h"

namespace btflut {

/// The file of an HSH model (order 2: 4 terms, order 3: 9). The model must be HSH.
Bytes encodeHshRtiFile(const LightModel& model);

}  // namespace btflut
