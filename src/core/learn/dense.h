#pragma once
// The dense kernels the networks spend their time in: products of float matrices and the ELU,
// forward and back. A file of their own so that the sanitized builds can leave them
// uninstrumented (src/core/CMakeLists.txt): under GCC's ASan and UBSan together Eigen's packed
// product and vectorised exp run 18 times slower, and a default bake took 5 minutes, not 20 s.
// Their callers stay instrumented, and every size is checked here.
//
//   dense::multiply(out, w, dense::Plain, x, dense::Plain);       // out = w x
//   dense::multiply(out, a, dense::Transposed, x, dense::Plain, dense::Add);  // out += a^T x

#include <Eigen/Dense>

namespace btflut {

using Matrix = Eigen::MatrixXf;
using Vector = Eigen::VectorXf;

namespace dense {

/// A column-major float matrix or a block of one, read or written in place.
using In = Eigen::Ref<const Matrix, 0, Eigen::OuterStride<>>;
using Out = Eigen::Ref<Matrix, 0, Eigen::OuterStride<>>;

enum Operand : bool { Plain = false, Transposed = true };
enum Store : bool { Assign = false, Add = true };

/// out = a b, or out += a b, with a and b as given or transposed; out has the product's size.
void multiply(Out out, In a, Operand aForm, In b, Operand bForm, Store store = Assign);
/// a's every column += b.
void addToColumns(Matrix& a, const Vector& b);
/// ELU in place: max(a, 0) + e^min(a, 0) - 1.
void elu(Matrix& a);
/// delta = back * ELU'(x), ELU's derivative from its output `activation`: min(activation, 0) + 1.
void eluBackward(Matrix& delta, const Matrix& back, const Matrix& activation);

}  // namespace dense
}  // namespace btflut
