// btflut info: what a bank holds.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/cli.h"
#include "core/bank_file.h"

namespace btflut::cli {

namespace {

struct InfoOptions {
    std::string bank;
};

std::string degrees(Direction d) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "(%.2f, %.2f)", d.thetaDegrees(), d.phiDegrees());
    return buf;
}

Status runInfo(const InfoOptions& o) {
    Result<LutBank> bank = loadBank(o.bank);
    if (!bank) return Error{bank.error()};
    const LutBank& b = *bank;
    std::cout << o.bank << ": btflut bank, format version " << bankFormatVersion(b) << ", "
              << std::filesystem::file_size(o.bank) << " bytes\n"
              << "  LUTs:      " << b.entries << " entries, "
              << (b.colour == ColourMode::Grey  ? "grey (one LUT on the grey value)"
                  : b.colour == ColourMode::Rgb ? "rgb (one LUT per channel)"
                                                : "lrgb (one LUT on the grey value, the albedo's chroma)")
              << "\n  reference: " << b.referenceName << ", light " << degrees(b.referenceLight)
              << ", view " << degrees(b.referenceView) << ", ";
    std::cout << b.reference.width << "x" << b.reference.height << "x" << b.reference.channels
              << " " << b.reference.bitDepth << "-bit, "
              << (b.reference.samples.empty() ? "not embedded" : "embedded") << "\n";
    if (b.makesLuts()) {
        if (b.blend.predictor == LutBank::Blend::Predictor::Ptm)
            std::cout << "  blend:     the PTM relit per light and matched, LUTs made at run time from ";
        else
            std::cout << "  blend:     " << b.blend.references.size() << " reference(s) blended per light, LUTs made at run "
                      << "time from ";
        std::cout << b.blend.quantiles << "-sample quantile functions; " << b.blend.regions << " region(s)";
        if (b.blend.regions > 1) {
            std::vector<std::size_t> texels(static_cast<std::size_t>(b.blend.regions), 0);
            for (std::size_t i = 0; i < b.blend.labels.size(); ++i) texels[b.blend.labels[i]] += b.blend.mask.inside[i];
            std::cout << " (sample pixels:";
            for (std::size_t n : texels) std::cout << " " << n;
            std::cout << ")";
        }
        std::cout << "\n";
        for (std::size_t k = 0; k < b.blend.lights.size(); ++k)
            std::cout << "    reference " << k << ": " << b.blend.lights[k].name << ", light "
                      << degrees(b.blend.lights[k].light) << "\n";
    }
    if (!b.ptm.empty())
        std::cout << "  ptm: " << b.ptm.width << "x" << b.ptm.height << ", 6 coefficients + RGB albedo per texel ("
                  << b.ptm.coefficients.size() + b.ptm.albedo.size() << " bytes)\n";
    if (!b.modelFill.empty())
        std::cout << "  model:     directions without measurements filled from " << b.modelFill << "\n";
    std::cout << "  grid:      " << b.gridSize << "x" << b.gridSize
              << " nodes per view layer over the equal-area light disk\n"
              << "  layers:    " << b.layers.size() << " view direction(s)\n"
              << "  domain:    " << domainName(b.domain)
              << (b.domain == BankDomain::Layers ? " (over each layer's lights, then between the layers' views)\n"
                                                 : " (over theta_i, theta_r and phi_i - phi_r: an isotropic material)\n");
    for (std::size_t l = 0; l < b.layers.size(); ++l) {
        const ViewLayer& layer = b.layers[l];
        std::size_t counts[4] = {0, 0, 0, 0}, modelled = 0;
        for (int j = 0; j < b.gridSize; ++j)
            for (int i = 0; i < b.gridSize; ++i) {
                DiskPoint p = b.gridPoint(i, j);
                if (p.x * p.x + p.y * p.y > 1) continue;  // beyond the horizon
                ++counts[static_cast<int>(layer.gridProvenance[static_cast<std::size_t>(j) * b.gridSize + i])];
            }
        double maxTheta = 0;
        for (const LightNode& n : layer.nodes) {
            modelled += n.modelled;
            if (!n.modelled) maxTheta = std::max(maxTheta, n.light.thetaDegrees());
        }
        // The share of light directions (by solid angle) where lookups interpolate; a grid
        // too coarse to have nodes inside the hemisphere (--grid 2) still has a coverage.
        char line[400];
        std::snprintf(line, sizeof line,
                      "  layer %zu: view %s, %zu light nodes (theta up to %.1f)%s, grid nodes in the "
                      "hemisphere: %zu measured, %zu interpolated, %zu modelled, %zu extrapolated; %.0f%% of light "
                      "directions covered by measurements%s\n",
                      l, degrees(layer.view).c_str(), layer.nodes.size() - modelled, maxTheta,
                      modelled ? (" + " + std::to_string(modelled) + " modelled").c_str() : "", counts[0], counts[1],
                      counts[3], counts[2], 100.0 * b.lightCoverage(l), modelled ? ", the rest modelled" : "");
        std::cout << line;
    }
    return success();
}

}  // namespace

void addInfoCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<InfoOptions>();
    CLI::App* app = root.add_subcommand("info", "Describe a LUT bank: header, grid, coverage, size");
    app->add_option("BANK", o->bank, "M.btflut")->required();
    commands.push_back({app, [o] { return runInfo(*o); }});
}

}  // namespace btflut::cli
