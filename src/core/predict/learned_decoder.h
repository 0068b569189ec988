#pragma once
// The learned model's decoder as networks (learned_model.h), for training and the CPU's
// evaluation: a light network gives, per light, each channel's weight on each code and an
// offset (a linear basis of the codes, as rbf and bln have, its light dependence learned),
// and a residual network of the codes and the light adds what no linear basis can (shadows,
// highlights):
//
//   pred_c(v, L) = sum_k A_ck(L) v_k + a_c(L) + r_c(v_1 .. v_N, h(L))
//
// with h(L) the light's features (its order-3 hemispherical harmonics, learned_model.h). The
// light network runs once per light (the GPU reads its output as uniforms), so a texel
// costs N C multiply-adds and the residual network's. Batches are light-major: sample
// l T + t is texel t under light l.

#include "core/learn/network.h"

namespace btflut {

struct LearnedDecoder {
    Network light;     ///< h(L) -> C (N + 1): row c (N + 1) + k is A_ck, row c (N + 1) + N is a_c
    Network residual;  ///< (v, h(L)) -> C

    int codes() const { return residual.inputs() - light.inputs(); }
    int channels() const { return residual.outputs(); }

    struct Pass {
        NetworkPass light, residual;
        Matrix codes, output;  ///< output: C x (L T)
        Matrix input;          ///< the residual network's, kept between steps
    };
    /// codes: N x T; lights: F x L (their features h).
    void forward(const Matrix& codes, const Matrix& lights, Pass& pass) const;

    struct Gradient {
        NetworkGradient light, residual;
        Matrix codes;  ///< d loss / d codes, N x T
    };
    Gradient backward(const Pass& pass, const Matrix& outputGradient) const;
};

}  // namespace btflut
