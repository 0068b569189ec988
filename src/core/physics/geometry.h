#pragma once
// Light/view geometries to simulate at.
//
//   curet-c2        the 11 in-plane positions of CUReT camera C2 (paper Fig. 3): light at
//                   0 degrees, camera at 45, sample normal at (k - 4) * 11.25 for k = 1..11,
//                   in the x-z plane; frontal to the lamp at 4 (L), specular at 6 (S),
//                   frontal to the camera at 8 (C). Named c2-1 .. c2-11.
//   curet-specular  the 7 specular positions theta_i = theta_r = 11.25 k, opposite azimuths.
//   rti-N           N lights spread evenly over the hemisphere up to 75 degrees (a Fibonacci
//                   spiral), frontal camera: an RTI dome. Named l1 .. lN.
//   a list          "THETA_I,PHI_I,THETA_R,PHI_R;..." in degrees.
//   a dataset       the directions of a dataset's images (any form openDataset reads).

#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/result.h"

namespace btflut {

struct Geometry {
    std::string name;
    Direction light;
    Direction view;
};

std::vector<Geometry> curetC2();
std::vector<Geometry> curetSpecular();
std::vector<Geometry> rtiDome(int lights);
/// A BTF: `n` view directions times `n` light directions, each set rtiDome(n)'s (names
/// vVV-lLL, view-major, as UBO2003 orders them).
std::vector<Geometry> btfDome(int n);

/// A named geometry, a list, or a dataset path. Errors name the problem. Angles may be 90
/// degrees here (the simulator handles the horizon); beyond is refused.
Result<std::vector<Geometry>> parseGeometry(const std::string& spec);

}  // namespace btflut
