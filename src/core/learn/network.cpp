#include "core/learn/network.h"

#include <cmath>

#include "core/check.h"

namespace btflut {

Network Network::random(const std::vector<int>& sizes, Random& random, WeightInit init) {
    BTFLUT_CHECK(sizes.size() >= 2);
    Network net;
    net.m_sizes = sizes;
    for (std::size_t k = 0; k + 1 < sizes.size(); ++k) {
        const float range = std::sqrt((init == WeightInit::Torch ? 1.f : 3.f) / static_cast<float>(sizes[k]));
        auto draw = [&] { return static_cast<float>(random.uniform() * 2 - 1) * range; };
        Matrix w(sizes[k + 1], sizes[k]);
        for (Eigen::Index r = 0; r < w.rows(); ++r)  // row by row: the order parameters() gives
            for (Eigen::Index c = 0; c < w.cols(); ++c) w(r, c) = draw();
        Vector b = Vector::Zero(sizes[k + 1]);
        if (init == WeightInit::Torch)
            for (Eigen::Index r = 0; r < b.size(); ++r) b(r) = draw();
        net.m_weights.push_back(std::move(w));
        net.m_biases.push_back(std::move(b));
    }
    return net;
}

std::size_t Network::parameterCount(const std::vector<int>& sizes) {
    std::size_t n = 0;
    for (std::size_t k = 0; k + 1 < sizes.size(); ++k)
        n += static_cast<std::size_t>(sizes[k] + 1) * static_cast<std::size_t>(sizes[k + 1]);
    return n;
}

std::size_t Network::multiplyAddCount(const std::vector<int>& sizes) {
    std::size_t n = 0;
    for (std::size_t k = 0; k + 1 < sizes.size(); ++k)
        n += static_cast<std::size_t>(sizes[k]) * static_cast<std::size_t>(sizes[k + 1]);
    return n;
}

Network Network::fromParameters(const std::vector<int>& sizes, const std::vector<float>& parameters) {
    BTFLUT_CHECK(sizes.size() >= 2 && parameters.size() == parameterCount(sizes));
    Network net;
    net.m_sizes = sizes;
    std::size_t at = 0;
    for (std::size_t k = 0; k + 1 < sizes.size(); ++k) {
        Matrix w(sizes[k + 1], sizes[k]);
        for (Eigen::Index r = 0; r < w.rows(); ++r)
            for (Eigen::Index c = 0; c < w.cols(); ++c) w(r, c) = parameters[at++];
        Vector b(sizes[k + 1]);
        for (Eigen::Index r = 0; r < b.size(); ++r) b(r) = parameters[at++];
        net.m_weights.push_back(std::move(w));
        net.m_biases.push_back(std::move(b));
    }
    return net;
}

std::vector<float> Network::parameters() const {
    std::vector<float> out;
    out.reserve(parameterCount(m_sizes));
    for (std::size_t k = 0; k < m_weights.size(); ++k) {
        for (Eigen::Index r = 0; r < m_weights[k].rows(); ++r)
            for (Eigen::Index c = 0; c < m_weights[k].cols(); ++c) out.push_back(m_weights[k](r, c));
        for (Eigen::Index r = 0; r < m_biases[k].size(); ++r) out.push_back(m_biases[k](r));
    }
    return out;
}

bool Network::finite() const {
    for (std::size_t k = 0; k < m_weights.size(); ++k)
        if (!m_weights[k].allFinite() || !m_biases[k].allFinite()) return false;
    return true;
}

void Network::forward(const Matrix& input, NetworkPass& pass) const {
    BTFLUT_CHECK(input.rows() == inputs());
    pass.input = input;
    pass.activations.resize(m_weights.size());
    const Matrix* x = &pass.input;
    for (std::size_t k = 0; k < m_weights.size(); ++k) {
        Matrix& a = pass.activations[k];
        a.resize(m_weights[k].rows(), x->cols());
        dense::multiply(a, m_weights[k], dense::Plain, *x, dense::Plain);
        dense::addToColumns(a, m_biases[k]);
        if (k + 1 < m_weights.size()) dense::elu(a);
        x = &a;
    }
}

void Network::backward(const NetworkPass& pass, const Matrix& outputGradient, bool inputGradient,
                       NetworkGradient& g) const {
    const std::size_t L = m_weights.size();
    g.weights.resize(L);
    g.biases.resize(L);
    Matrix& delta = pass.delta;  // d loss / d the layer's pre-activation
    Matrix& back = pass.back;
    delta = outputGradient;
    for (std::size_t k = L; k-- > 0;) {
        const Matrix& x = k == 0 ? pass.input : pass.activations[k - 1];
        g.weights[k].resize(delta.rows(), x.rows());
        dense::multiply(g.weights[k], delta, dense::Plain, x, dense::Transposed);
        g.biases[k] = delta.rowwise().sum();
        if (k == 0 && !inputGradient) break;
        Matrix& to = k == 0 ? g.input : back;
        to.resize(m_weights[k].cols(), delta.cols());
        dense::multiply(to, m_weights[k], dense::Transposed, delta, dense::Plain);
        if (k == 0) break;
        dense::eluBackward(delta, back, pass.activations[k - 1]);
    }
}

Adam::Adam(const Network& network, bool amsgrad) : m_amsgrad(amsgrad) {
    for (std::size_t k = 0; k < network.layers(); ++k) {
        const Matrix& w = network.weights(k);
        m_weightMean.push_back(Matrix::Zero(w.rows(), w.cols()));
        m_weightSquare.push_back(Matrix::Zero(w.rows(), w.cols()));
        m_biasMean.push_back(Vector::Zero(w.rows()));
        m_biasSquare.push_back(Vector::Zero(w.rows()));
        if (amsgrad) {
            m_weightSquareMax.push_back(Matrix::Zero(w.rows(), w.cols()));
            m_biasSquareMax.push_back(Vector::Zero(w.rows()));
        }
    }
}

void Adam::step(Network& network, const NetworkGradient& gradient, float rate) {
    constexpr float beta1 = 0.9f, beta2 = 0.999f, epsilon = 1e-8f;
    ++m_steps;
    const float c1 = 1 - std::pow(beta1, static_cast<float>(m_steps)),
                c2 = 1 - std::pow(beta2, static_cast<float>(m_steps));
    auto update = [&](auto& parameter, auto& mean, auto& square, auto* squareMax, const auto& g) {
        mean = beta1 * mean + (1 - beta1) * g;
        square = beta2 * square + (1 - beta2) * g.cwiseAbs2();
        if (squareMax) *squareMax = squareMax->cwiseMax(square);
        const auto& divisor = squareMax ? *squareMax : square;
        parameter.array() -= rate * (mean.array() / c1) / ((divisor.array() / c2).sqrt() + epsilon);
    };
    for (std::size_t k = 0; k < network.layers(); ++k) {
        update(network.weights(k), m_weightMean[k], m_weightSquare[k], m_amsgrad ? &m_weightSquareMax[k] : nullptr,
               gradient.weights[k]);
        update(network.bias(k), m_biasMean[k], m_biasSquare[k], m_amsgrad ? &m_biasSquareMax[k] : nullptr,
               gradient.biases[k]);
    }
}

void addGradient(NetworkGradient& into, const NetworkGradient& g) {
    for (std::size_t k = 0; k < into.weights.size(); ++k) {
        into.weights[k] += g.weights[k];
        into.biases[k] += g.biases[k];
    }
}

}  // namespace btflut
