#pragma once
// A small fully connected network: layers of weights W_k (outputs x inputs) and biases b_k,
// an ELU between layers, the last layer linear. Batches are matrices with one column per
// sample. What the learned predictor (predict/learned_model.h) trains and evaluates.
//
//   Network net = Network::random({11, 24, 24, 3}, random);
//   NetworkPass pass;
//   net.forward(inputs, pass);                   // pass.output(): outputs x batch
//   NetworkGradient g = net.backward(pass, dOutput, true);   // g.input: d loss / d inputs
//   Adam adam(net);  adam.step(net, g, 1e-3f);

#include <cstdint>
#include <vector>

#include "core/learn/dense.h"
#include "core/random.h"

namespace btflut {

/// One batch's activations, kept for the backward pass.
struct NetworkPass {
    Matrix input;
    std::vector<Matrix> activations;  ///< after each layer (ELU but the last)
    const Matrix& output() const { return activations.back(); }
    /// The backward pass's working matrices, kept so that a step allocates nothing (a batch's
    /// matrices are beyond malloc's mmap threshold: each new one costs page faults).
    mutable Matrix delta, back;
};

/// d loss / d parameters of each layer, and (when asked) d loss / d inputs.
struct NetworkGradient {
    std::vector<Matrix> weights;
    std::vector<Vector> biases;
    Matrix input;
};

/// Adds g's parameter gradients (not its input's) to `into`'s, of the same network.
void addGradient(NetworkGradient& into, const NetworkGradient& g);

/// How random() draws a layer's parameters.
enum class WeightInit {
    UnitVariance,  ///< weights uniform in +-sqrt(3 / inputs) (unit variance through each layer), biases 0
    Torch,         ///< PyTorch's nn.Linear default: weights and biases uniform in +-1 / sqrt(inputs)
};

class Network {
public:
    Network() = default;
    static Network random(const std::vector<int>& sizes, Random& random, WeightInit init = WeightInit::UnitVariance);
    /// From its parameters as parameters() gives them; sizes: inputs, hidden..., outputs.
    static Network fromParameters(const std::vector<int>& sizes, const std::vector<float>& parameters);

    const std::vector<int>& sizes() const { return m_sizes; }
    int inputs() const { return m_sizes.front(); }
    int outputs() const { return m_sizes.back(); }
    std::size_t layers() const { return m_weights.size(); }
    static std::size_t parameterCount(const std::vector<int>& sizes);
    /// Multiply-adds of one input's forward pass.
    static std::size_t multiplyAddCount(const std::vector<int>& sizes);
    /// Per layer its weights (row-major: an output's inputs together), then its biases.
    std::vector<float> parameters() const;
    bool finite() const;

    Matrix& weights(std::size_t layer) { return m_weights[layer]; }
    const Matrix& weights(std::size_t layer) const { return m_weights[layer]; }
    Vector& bias(std::size_t layer) { return m_biases[layer]; }
    const Vector& bias(std::size_t layer) const { return m_biases[layer]; }

    void forward(const Matrix& input, NetworkPass& pass) const;
    /// Backpropagates d loss / d output through the pass into `g` (its matrices reused).
    void backward(const NetworkPass& pass, const Matrix& outputGradient, bool inputGradient, NetworkGradient& g) const;
    NetworkGradient backward(const NetworkPass& pass, const Matrix& outputGradient, bool inputGradient) const {
        NetworkGradient g;
        backward(pass, outputGradient, inputGradient, g);
        return g;
    }

private:
    std::vector<int> m_sizes;
    std::vector<Matrix> m_weights;
    std::vector<Vector> m_biases;
};

/// Adam (Kingma & Ba 2015) with its moments per parameter; with `amsgrad`, AMSGrad (Reddi et
/// al. 2018: the step divides by the largest second moment so far), as PyTorch's amsgrad=True.
class Adam {
public:
    explicit Adam(const Network& network, bool amsgrad = false);
    void step(Network& network, const NetworkGradient& gradient, float rate);

private:
    bool m_amsgrad;
    std::vector<Matrix> m_weightMean, m_weightSquare, m_weightSquareMax;
    std::vector<Vector> m_biasMean, m_biasSquare, m_biasSquareMax;
    int m_steps = 0;
};

/// ELU: x above 0, e^x - 1 below.
inline float elu(float x) { return x > 0 ? x : std::exp(x) - 1; }

}  // namespace btflut
