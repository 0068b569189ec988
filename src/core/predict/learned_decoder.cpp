#include "core/predict/learned_decoder.h"

#include "core/predict/learned_training.h"

namespace btflut {

void LearnedDecoder::forward(const Matrix& codes, const Matrix& lights, Pass& pass) const {
    const Eigen::Index N = codes.rows(), T = codes.cols(), L = lights.cols(), C = channels();
    pass.codes = codes;
    light.forward(lights, pass.light);
    codesBesideLights(codes, lights, pass.input);
    residual.forward(pass.input, pass.residual);
    pass.output = pass.residual.output();
    const Matrix& basis = pass.light.output();
    for (Eigen::Index l = 0; l < L; ++l) {
        // A(L) is C x N: channel c's row is basis rows c (N + 1) .. c (N + 1) + N - 1.
        const Eigen::Map<const Matrix, 0, Eigen::OuterStride<>> A(basis.col(l).data(), N, C,
                                                                  Eigen::OuterStride<>(N + 1));
        auto out = pass.output.block(0, l * T, C, T);
        dense::multiply(out, A, dense::Transposed, codes, dense::Plain, dense::Add);
        for (Eigen::Index c = 0; c < C; ++c) out.row(c).array() += basis(c * (N + 1) + N, l);
    }
}

LearnedDecoder::Gradient LearnedDecoder::backward(const Pass& pass, const Matrix& outputGradient) const {
    const Eigen::Index N = pass.codes.rows(), T = pass.codes.cols(), L = pass.light.output().cols(), C = channels();
    Gradient g;
    g.residual = residual.backward(pass.residual, outputGradient, true);
    g.codes = Matrix::Zero(N, T);
    Matrix basisGradient(C * (N + 1), L);
    const Matrix& basis = pass.light.output();
    for (Eigen::Index l = 0; l < L; ++l) {
        const auto d = outputGradient.block(0, l * T, C, T);
        g.codes += g.residual.input.block(0, l * T, N, T);
        const Eigen::Map<const Matrix, 0, Eigen::OuterStride<>> A(basis.col(l).data(), N, C,
                                                                  Eigen::OuterStride<>(N + 1));
        dense::multiply(g.codes, A, dense::Plain, d, dense::Plain, dense::Add);
        Eigen::Map<Matrix, 0, Eigen::OuterStride<>> dA(basisGradient.col(l).data(), N, C, Eigen::OuterStride<>(N + 1));
        dense::multiply(dA, pass.codes, dense::Plain, d, dense::Transposed);
        for (Eigen::Index c = 0; c < C; ++c) basisGradient(c * (N + 1) + N, l) = d.row(c).sum();
    }
    g.light = light.backward(pass.light, basisGradient, false);
    return g;
}

}  // namespace btflut
