#include "core/learn/dense.h"

#include "core/check.h"

namespace btflut::dense {
namespace {

template <class A, class B>
void store(Out out, const A& a, const B& b, Store how) {
    if (how == Add)
        out.noalias() += a * b;
    else
        out.noalias() = a * b;
}

}  // namespace

void multiply(Out out, In a, Operand aForm, In b, Operand bForm, Store how) {
    const Eigen::Index rows = aForm == Transposed ? a.cols() : a.rows(),
                       depth = aForm == Transposed ? a.rows() : a.cols(),
                       cols = bForm == Transposed ? b.rows() : b.cols();
    BTFLUT_CHECK(depth == (bForm == Transposed ? b.cols() : b.rows()));
    BTFLUT_CHECK(out.rows() == rows && out.cols() == cols);
    if (aForm == Transposed && bForm == Transposed)
        store(out, a.transpose(), b.transpose(), how);
    else if (aForm == Transposed)
        store(out, a.transpose(), b, how);
    else if (bForm == Transposed)
        store(out, a, b.transpose(), how);
    else
        store(out, a, b, how);
}

void addToColumns(Matrix& a, const Vector& b) {
    BTFLUT_CHECK(a.rows() == b.size());
    a.colwise() += b;
}

// Whole-array operations: Eigen vectorises exp there, not inside a select.
void elu(Matrix& a) { a.array() = a.array().max(0.f) + (a.array().min(0.f).exp() - 1.f); }

void eluBackward(Matrix& delta, const Matrix& back, const Matrix& activation) {
    BTFLUT_CHECK(back.rows() == activation.rows() && back.cols() == activation.cols());
    delta.resize(back.rows(), back.cols());
    delta.array() = back.array() * (activation.array().min(0.f) + 1.f);
}

}  // namespace btflut::dense
