// Fitting linear light models (light_model.h) to the images of one view: least squares per
// texel for the fixed bases (ptm, hsh), PCA over the sample texels for rbf and bln.
#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/check.h"
#include "core/parallel.h"
#include "core/predict/light_model.h"

namespace btflut {

namespace {

// Planes as codes: each plane's range over every texel mapped onto 0..255 (0..15 for the
// 4-bit planes), as the .ptm format and RTI web formats store them: one scale and bias per plane.
void quantisePlanes(const std::vector<double>& values, LightModel& m) {
    const auto P = static_cast<std::size_t>(m.planes);
    const std::size_t texels = m.texels();
    m.scale.assign(P, 1.f);
    m.bias.assign(P, 0.f);
    m.coefficients.resize(texels * P);
    for (std::size_t p = 0; p < P; ++p) {
        double low = values[p], high = values[p];
        for (std::size_t i = 0; i < texels; ++i) {
            low = std::min(low, values[i * P + p]);
            high = std::max(high, values[i * P + p]);
        }
        const int top = m.maxCode(static_cast<int>(p));
        const double scale = high > low ? (high - low) / top : 1.0;
        m.scale[p] = static_cast<float>(scale);
        m.bias[p] = static_cast<float>(-low / scale);
        for (std::size_t i = 0; i < texels; ++i)
            m.coefficients[i * P + p] = static_cast<std::uint8_t>(
                std::clamp<long>(std::lround(values[i * P + p] / m.scale[p] + m.bias[p]), 0, top));
    }
}

// The albedo of the LRGB layout: the texel's mean colour, its largest channel 255; and the
// factor that brings the grey value to the largest channel's (what the luminance then fits).
void albedoOf(const std::vector<const Image*>& images, LightModel& m, std::vector<double>& luminanceScale) {
    const std::size_t texels = m.texels();
    m.albedo.resize(texels * 3);
    luminanceScale.assign(texels, 1.0);
    for (std::size_t i = 0; i < texels; ++i) {
        std::array<double, 3> sum{};
        for (const Image* image : images)
            for (std::size_t c = 0; c < 3; ++c) sum[c] += image->samples[i * 3 + c];
        const double grey = (sum[0] + sum[1] + sum[2]) / 3, top = std::max({sum[0], sum[1], sum[2]});
        luminanceScale[i] = grey > 0 ? top / grey : 1.0;
        for (std::size_t c = 0; c < 3; ++c)
            m.albedo[i * 3 + c] = static_cast<std::uint8_t>(top > 0 ? std::lround(255 * sum[c] / top) : 255);
    }
}

Result<LightModel> fitFixedBasis(const std::vector<const Image*>& images, const std::vector<Direction>& lights,
                                 const LightModelOptions& o, const std::string& what) {
    LightModel m;
    m.basis = o.basis;
    m.order = o.basis == LightBasis::Hsh ? o.order : 0;
    if (o.basis == LightBasis::Hsh && m.order != 2 && m.order != 3)
        return Error{"hsh order " + std::to_string(o.order) + ": expected 2 (4 terms) or 3 (9 terms)"};
    const int K = LightModel::termCount(o.basis, m.order);
    const auto k = static_cast<std::size_t>(K);
    m.width = images.front()->width;
    m.height = images.front()->height;
    m.planes = m.wide = K;
    m.channels = 1;
    const std::size_t texels = m.texels();
    std::vector<double> luminanceScale(texels, 1.0);
    if (images.front()->channels == 3) albedoOf(images, m, luminanceScale);

    // The normal equations (the same for every texel), ridge-regularised where the lights
    // leave the terms ill-determined: a basis whose terms barely vary over the measured
    // lights (HSH of order 3 under lights within 40 degrees of the normal) would otherwise
    // amplify noise into a collapsed relighting.
    Eigen::MatrixXd A(lights.size(), K);
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const std::vector<double> t = basisTerms(o.basis, m.order, lights[i]);
        for (std::size_t j = 0; j < k; ++j) A(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = t[j];
    }
    Eigen::MatrixXd normal = A.transpose() * A;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(normal);
    const double top = svd.singularValues()(0);
    if (!(top > 0) || !std::isfinite(top))
        return Error{what + ": the light directions determine none of the " + std::string(lightBasisName(o.basis)) +
                     " terms"};
    const double condition = top / std::max(svd.singularValues()(K - 1), 1e-300);
    if (condition > 1e3) normal += Eigen::MatrixXd::Identity(K, K) * (top * 1e-3);
    const Eigen::MatrixXd solve = normal.inverse() * A.transpose();  // K x lights

    std::vector<double> fitted(texels * k);
    parallelFor((texels + 4095) / 4096, o.threads, [&](std::size_t block) {
        const std::size_t end = std::min(texels, (block + 1) * 4096);
        Eigen::VectorXd grey(static_cast<Eigen::Index>(images.size()));
        for (std::size_t i = block * 4096; i < end; ++i) {
            for (std::size_t l = 0; l < images.size(); ++l) grey(static_cast<Eigen::Index>(l)) = images[l]->grey(i);
            const Eigen::VectorXd a = solve * grey * luminanceScale[i];
            for (std::size_t j = 0; j < k; ++j) fitted[i * k + j] = a(static_cast<Eigen::Index>(j));
        }
    });
    quantisePlanes(fitted, m);
    return m;
}

// The packed layout's split: with `bytes` per texel, `wide` 8-bit components and
// 2 (bytes - wide) 4-bit ones, where the training images are reconstructed best: the
// variance of the components left out plus the quantisation error of those kept (the
// components are orthonormal, so the errors add), over the sample texels.
void chooseSplit(const std::vector<double>& coordinates, const std::vector<double>& variance,
                 const std::vector<std::uint32_t>& sample, int bytes, LightModel& m) {
    const auto P = static_cast<std::size_t>(m.planes);
    const std::size_t texels = coordinates.size() / P;
    // Each component's mean squared quantisation error with 8 and with 4 bits.
    std::vector<std::array<double, 2>> error(P);
    for (std::size_t p = 0; p < P; ++p) {
        double low = coordinates[p], high = coordinates[p];
        for (std::size_t i = 0; i < texels; ++i) {
            low = std::min(low, coordinates[i * P + p]);
            high = std::max(high, coordinates[i * P + p]);
        }
        for (int k = 0; k < 2; ++k) {
            const double step = std::max(high - low, 1e-30) / (k == 0 ? 255 : 15);
            double sum = 0;
            for (std::uint32_t i : sample) {
                const double v = coordinates[i * P + p] - low;
                const double d = v - std::round(v / step) * step;
                sum += d * d;
            }
            error[p][static_cast<std::size_t>(k)] = sum / static_cast<double>(sample.size());
        }
    }
    double best = INFINITY;
    for (int wide = std::min(bytes, static_cast<int>(P)); wide >= 0; --wide) {
        const int planes = std::min(static_cast<int>(P), wide + 2 * (bytes - wide));
        double cost = 0;
        for (std::size_t p = 0; p < P; ++p)
            cost += static_cast<int>(p) >= planes ? variance[p] : error[p][static_cast<int>(p) < wide ? 0 : 1];
        if (planes >= 1 && cost < best) best = cost, m.wide = wide, m.planes = planes;
    }
}

// The training lights' rows of a PCA model blended by normalised Gaussians of width sigma,
// each row left out of its own prediction: the squared error of predicting every row from
// the others, each plane's part weighted by its variance (so it is the expected squared
// error over the texels).
double leaveOneOutError(const std::vector<Direction>& lights, const std::vector<float>& table, std::size_t row,
                        std::size_t channels, const std::vector<double>& variance, double sigma) {
    double error = 0;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const Vec3 l = toVector(lights[i]);
        std::vector<double> sum(row, 0.0);
        double total = 0;
        for (std::size_t j = 0; j < lights.size(); ++j) {
            if (j == i) continue;
            const Vec3 m = toVector(lights[j]);
            const double d2 = (l.x - m.x) * (l.x - m.x) + (l.y - m.y) * (l.y - m.y) + (l.z - m.z) * (l.z - m.z);
            const double g = std::exp(-d2 / (sigma * sigma));
            total += g;
            for (std::size_t k = 0; k < row; ++k) sum[k] += g * table[j * row + k];
        }
        if (!(total > 1e-300)) return INFINITY;
        for (std::size_t k = 0; k < row; ++k) {
            const double d = sum[k] / total - table[i * row + k];
            error += d * d * (k < channels ? 1.0 : variance[k / channels - 1]);
        }
    }
    return error;
}

// The grid of a bln model: at each node the rows that fit the training lights' rows best
// when read bilinearly, pulled towards the rbf blend at the node where the lights leave the
// grid undetermined: min |A V - T|^2 + k |V - B T|^2, A the lights' bilinear weights on the
// grid, B the nodes' rbf weights over the lights.
std::vector<float> resampleOnGrid(const LightModel& rbf, int grid) {
    const std::size_t n = rbf.lights.size(), nodes = static_cast<std::size_t>(grid) * grid;
    const std::size_t row = (1 + static_cast<std::size_t>(rbf.planes)) * static_cast<std::size_t>(rbf.channels);
    Eigen::MatrixXd T(n, row), A = Eigen::MatrixXd::Zero(n, nodes), B(nodes, n);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t k = 0; k < row; ++k) T(i, k) = rbf.table[i * row + k];
    for (std::size_t i = 0; i < n; ++i) {
        const DiskPoint p = toDisk(rbf.lights[i]);
        const double gx = std::clamp((p.x + 1) / 2 * (grid - 1), 0.0, grid - 1.0);
        const double gy = std::clamp((p.y + 1) / 2 * (grid - 1), 0.0, grid - 1.0);
        const int x = std::min(static_cast<int>(gx), grid - 2), y = std::min(static_cast<int>(gy), grid - 2);
        const double fx = gx - x, fy = gy - y;
        A(i, y * grid + x) = (1 - fx) * (1 - fy);
        A(i, y * grid + x + 1) = fx * (1 - fy);
        A(i, (y + 1) * grid + x) = (1 - fx) * fy;
        A(i, (y + 1) * grid + x + 1) = fx * fy;
    }
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            const Direction node = fromDisk({-1 + 2.0 * i / (grid - 1), -1 + 2.0 * j / (grid - 1)});
            const Vec3 l = toVector(node);
            double total = 0;
            std::vector<double> g(n);
            for (std::size_t k = 0; k < n; ++k) {
                const Vec3 m = toVector(rbf.lights[k]);
                const double d2 = (l.x - m.x) * (l.x - m.x) + (l.y - m.y) * (l.y - m.y) + (l.z - m.z) * (l.z - m.z);
                g[k] = std::exp(-d2 / (double{rbf.sigma} * rbf.sigma));
                total += g[k];
            }
            std::size_t nearest = 0;
            for (std::size_t k = 1; k < n; ++k)
                if (angleBetween(rbf.lights[k], node) < angleBetween(rbf.lights[nearest], node)) nearest = k;
            for (std::size_t k = 0; k < n; ++k)
                B(static_cast<Eigen::Index>(j * grid + i), static_cast<Eigen::Index>(k)) =
                    total > 1e-300 ? g[k] / total : (k == nearest ? 1.0 : 0.0);
        }
    const double k = 0.1;
    const Eigen::MatrixXd prior = B * T;
    const Eigen::MatrixXd V =
        prior +
        (A.transpose() * A + k * Eigen::MatrixXd::Identity(nodes, nodes)).ldlt().solve(A.transpose() * (T - A * prior));
    std::vector<float> out(nodes * row);
    for (std::size_t i = 0; i < nodes; ++i)
        for (std::size_t c = 0; c < row; ++c) out[i * row + c] = static_cast<float>(V(i, c));
    return out;
}

// A texel's value in dimension d of the image stack: image d / C, channel d % C (or the grey).
struct StackValues {
    const std::vector<const Image*>& images;
    std::size_t C;
    double operator()(std::size_t texel, std::size_t d) const {
        const Image& image = *images[d / C];
        return C == 1 ? image.grey(texel) : image.samples[texel * 3 + d % C];
    }
};

// The stack's mean over the sample's texels and its largest P principal components (columns
// of E), with their variances.
struct Components {
    Eigen::VectorXd mean;
    Eigen::MatrixXd E;
    std::vector<double> variance;
};

Result<Components> principalComponents(const StackValues& value, std::size_t D, std::size_t P,
                                       const std::vector<std::uint32_t>& sample, int threads, const std::string& what) {
    // Mean and covariance over (at most about 2^16 of) the sample's texels.
    const std::size_t step = std::max<std::size_t>(1, sample.size() / 65536);
    std::vector<std::uint32_t> used;
    for (std::size_t i = 0; i < sample.size(); i += step) used.push_back(sample[i]);
    const std::size_t blocks = std::min<std::size_t>(16, used.size());
    std::vector<Eigen::MatrixXd> partial(blocks, Eigen::MatrixXd::Zero(D, D));
    std::vector<Eigen::VectorXd> partialMean(blocks, Eigen::VectorXd::Zero(D));
    parallelFor(blocks, threads, [&](std::size_t b) {
        Eigen::VectorXd x(D);
        for (std::size_t s = b; s < used.size(); s += blocks) {
            for (std::size_t d = 0; d < D; ++d) x(d) = value(used[s], d);
            partial[b].selfadjointView<Eigen::Lower>().rankUpdate(x);
            partialMean[b] += x;
        }
    });
    Eigen::MatrixXd second = Eigen::MatrixXd::Zero(D, D);
    Components out{Eigen::VectorXd::Zero(D), Eigen::MatrixXd(D, P), std::vector<double>(P)};
    for (std::size_t b = 0; b < blocks; ++b) {
        second += partial[b];
        out.mean += partialMean[b];
    }
    const auto count = static_cast<double>(used.size());
    out.mean /= count;
    Eigen::MatrixXd covariance = second.selfadjointView<Eigen::Lower>();
    covariance = covariance / count - out.mean * out.mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(covariance);
    if (eigen.info() != Eigen::Success) return Error{what + ": the images' principal components did not converge"};
    // The largest P components (the solver sorts ascending).
    for (std::size_t p = 0; p < P; ++p) {
        out.E.col(static_cast<Eigen::Index>(p)) = eigen.eigenvectors().col(static_cast<Eigen::Index>(D - 1 - p));
        out.variance[p] = std::max(0.0, eigen.eigenvalues()(static_cast<Eigen::Index>(D - 1 - p)));
    }
    return out;
}

// Each texel's coordinates on the components, texels x P.
std::vector<double> projectTexels(const StackValues& value, const Components& pca, std::size_t texels, int threads) {
    const auto D = static_cast<std::size_t>(pca.E.rows()), P = static_cast<std::size_t>(pca.E.cols());
    std::vector<double> coordinates(texels * P);
    parallelFor((texels + 4095) / 4096, threads, [&](std::size_t block) {
        const std::size_t end = std::min(texels, (block + 1) * 4096);
        Eigen::VectorXd x(D);
        for (std::size_t i = block * 4096; i < end; ++i) {
            for (std::size_t d = 0; d < D; ++d) x(d) = value(i, d) - pca.mean(d);
            const Eigen::VectorXd c = pca.E.transpose() * x;
            for (std::size_t p = 0; p < P; ++p) coordinates[i * P + p] = c(static_cast<Eigen::Index>(p));
        }
    });
    return coordinates;
}

// sigma: the multiple of the lights' median spacing that predicts each light's row best from
// the others.
float chooseSigma(const std::vector<Direction>& lights, const std::vector<float>& table, std::size_t row, std::size_t C,
                  const std::vector<double>& variance) {
    const std::size_t n = lights.size();
    std::vector<double> spacing;
    for (std::size_t i = 0; i < n; ++i) {
        double nearest = INFINITY;
        const Vec3 a = toVector(lights[i]);
        for (std::size_t j = 0; j < n; ++j) {
            if (j == i) continue;
            const Vec3 b = toVector(lights[j]);
            const double d =
                std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
            if (d > 1e-9) nearest = std::min(nearest, d);
        }
        if (std::isfinite(nearest)) spacing.push_back(nearest);
    }
    std::sort(spacing.begin(), spacing.end());
    const double unit = spacing.empty() ? 0.1 : std::max(spacing[spacing.size() / 2], 1e-3);
    double best = INFINITY;
    auto sigma = static_cast<float>(unit);
    for (double factor : {0.35, 0.5, 0.7, 1.0, 1.4, 2.0, 2.8, 4.0}) {
        const double e = n > 1 ? leaveOneOutError(lights, table, row, C, variance, unit * factor) : 0;
        if (e < best) best = e, sigma = static_cast<float>(unit * factor);
    }
    return sigma;
}

Result<LightModel> fitPca(const std::vector<const Image*>& images, const std::vector<Direction>& lights,
                          const Mask& mask, const LightModelOptions& o, const std::string& what) {
    const Image& first = *images.front();
    LightModel m;
    m.basis = o.basis;
    m.width = first.width;
    m.height = first.height;
    m.channels = o.colour && first.channels == 3 ? 3 : 1;
    const auto C = static_cast<std::size_t>(m.channels), n = images.size();
    const std::size_t D = n * C;
    if (o.planes < 1 || o.planes > LightModel::kMaxPlanes)
        return Error{std::string(lightBasisName(o.basis)) + ": " + std::to_string(o.planes) + " planes is outside 1.." +
                     std::to_string(LightModel::kMaxPlanes)};
    // Packed: up to two components per byte; the split between 8-bit and 4-bit ones is chosen
    // below, from the components' variances and quantisation errors.
    const std::size_t most = o.packed
                                 ? std::min<std::size_t>(2 * static_cast<std::size_t>(o.planes), LightModel::kMaxPlanes)
                                 : static_cast<std::size_t>(o.planes);
    m.planes = m.wide = static_cast<int>(std::min(most, D));
    const auto P = static_cast<std::size_t>(m.planes);
    const StackValues value{images, C};

    std::vector<std::uint32_t> sample;
    for (std::size_t i = 0; i < mask.inside.size(); ++i)
        if (mask.inside[i]) sample.push_back(static_cast<std::uint32_t>(i));
    if (sample.empty()) return Error{what + ": the mask has no sample pixels"};
    Result<Components> pca = principalComponents(value, D, P, sample, o.threads, what);
    if (!pca) return Error{pca.error()};
    std::vector<double> coordinates = projectTexels(value, *pca, m.texels(), o.threads);
    if (o.packed) {
        chooseSplit(coordinates, pca->variance, sample, o.planes, m);
        if (static_cast<std::size_t>(m.planes) < P) {  // fewer components kept: drop the rest
            std::vector<double> kept;
            for (std::size_t i = 0; i < m.texels(); ++i)
                kept.insert(kept.end(), coordinates.begin() + static_cast<std::ptrdiff_t>(i * P),
                            coordinates.begin() + static_cast<std::ptrdiff_t>(i * P) + m.planes);
            coordinates = std::move(kept);
            pca->E.conservativeResize(Eigen::NoChange, m.planes);
        }
    }
    quantisePlanes(coordinates, m);
    const auto kept = static_cast<std::size_t>(m.planes);

    // Per training light: the mean's values there, then each component's.
    const std::size_t row = (1 + kept) * C;
    m.lights = lights;
    m.table.resize(n * row);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t c = 0; c < C; ++c) {
            m.table[i * row + c] = static_cast<float>(pca->mean(i * C + c));
            for (std::size_t p = 0; p < kept; ++p)
                m.table[i * row + (1 + p) * C + c] = static_cast<float>(pca->E(i * C + c, p));
        }
    m.sigma = chooseSigma(lights, m.table, row, C, pca->variance);
    if (o.basis == LightBasis::Bilinear) {
        if (o.grid < 2 || o.grid > 64) return Error{"bln grid " + std::to_string(o.grid) + " is outside 2..64"};
        m.grid = o.grid;
        m.table = resampleOnGrid(m, o.grid);
        m.lights.clear();
        m.sigma = 0;
    }
    return m;
}

}  // namespace

Result<LightModel> fitLightModel(const std::vector<const Image*>& images, const std::vector<Direction>& lights,
                                 const Mask& mask, const LightModelOptions& options, const std::string& what) {
    BTFLUT_CHECK(images.size() == lights.size());
    if (images.empty()) return Error{what + ": no images to fit a light model to"};
    for (const Image* image : images)
        BTFLUT_CHECK(image->width == images.front()->width && image->height == images.front()->height &&
                     image->channels == images.front()->channels);
    if (options.basis == LightBasis::Ptm || options.basis == LightBasis::Hsh)
        return fitFixedBasis(images, lights, options, what);
    return fitPca(images, lights, mask, options, what);
}

}  // namespace btflut
