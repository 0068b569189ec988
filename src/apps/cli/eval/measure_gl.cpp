// btflut eval: the GL figures (frame times, texture bytes, GPU against CPU).
#include <algorithm>
#include <chrono>
#include <memory>

#include "cli/cli.h"
#include "cli/eval/eval.h"
#include "core/relight/relighter.h"
#include "gl/context.h"
#include "gl/native_renderer.h"
#include "gl/scene_renderer.h"

namespace btflut::cli::eval {

Status measureGl(std::vector<Variant>& variants, const std::map<std::string, std::string>& bankFiles,
                 const Dataset& dataset, const EvalOptions& o, std::string& context) {
    Result<GlBackend> backend = parseGlBackend(o.backend);
    if (!backend) return Error{backend.error()};
    Result<std::unique_ptr<HeadlessContext>> gl = createHeadlessContext(*backend);
    if (!gl) return Error{gl.error()};
    context = (*gl)->description();
    std::vector<std::unique_ptr<SceneRenderer>> renderers;
    for (Variant& v : variants) {
        // No render mode draws a model on its own.
        if (v.unmatched()) {
            renderers.emplace_back();
            continue;
        }
        Result<std::unique_ptr<SceneRenderer>> r =
            SceneRenderer::create(benchScene(bankFiles.at(v.name), 1024, 1024, dataset.source));
        if (!r) return Error{r.error()};
        renderers.push_back(std::move(*r));
    }
    std::vector<std::vector<double>> times(variants.size());
    for (int round = 0; round < 3; ++round)
        for (std::size_t i = 0; i < variants.size(); ++i)
            for (int f = 0; f < o.frames && renderers[i]; ++f) {
                const auto start = Clock::now();
                if (Status s = renderers[i]->draw(benchLights()[static_cast<std::size_t>(f % 2)], variants[i].mode); !s)
                    return s;
                renderers[i]->finish();
                if (round > 0 || f > 0) times[i].push_back(seconds(start) * 1e3);  // the first frame uploads
            }
    for (std::size_t i = 0; i < variants.size(); ++i) {
        Variant& v = variants[i];
        if (!renderers[i]) continue;
        v.frameMs = median(times[i]);
        const RenderStats& stats = renderers[i]->stats();
        const TextureBytes& b = stats.textureBytes;
        const LutBank* bank = renderers[i]->bank("m");
        const double texels = static_cast<double>(bank->reference.pixelCount());
        const double quads = static_cast<double>(std::max<std::size_t>(stats.quadsDrawn, 1));
        double bytes = 0;
        switch (v.mode) {
            case RenderMode::Lut:  // what it reads, and one relit texture (per light direction)
                bytes =
                    static_cast<double>(bank->makesLuts() ? b.prediction : b.reference) +
                    static_cast<double>(b.luts) / quads +
                    static_cast<double>(b.relit) / static_cast<double>(std::max<std::size_t>(stats.relitTextures, 1));
                break;
            case RenderMode::Ptm:
                bytes = static_cast<double>(b.ptm);
                break;
            case RenderMode::Nearest:
                bytes =
                    static_cast<double>(b.images) / static_cast<double>(std::max<std::size_t>(stats.imagesLoaded, 1));
                break;
            default:
                bytes = static_cast<double>(b.reference);
                break;
        }
        v.gpuBytesPerTexel = bytes / texels;
        if (v.mode == RenderMode::Lut && !v.blendedLuts) {
            // The native renderer against the CPU relighting, at the first held-out light.
            const Direction light = dataset.images.front().light;
            Result<Image> native = renderNative(*bank, light, bank->referenceView, true);
            if (!native) return Error{native.error()};
            const Relighter relighter(*bank);
            const Image cpu = quantised(relighter.apply(relighter.frame(light, bank->referenceView), true), 8);
            const Image gpu = quantised(*native, 8);
            double worst = 0;
            for (std::size_t s = 0; s < cpu.samples.size(); ++s)
                worst = std::max(worst, std::abs(static_cast<double>(cpu.samples[s]) - gpu.samples[s]) * 255.0);
            v.gpuMaxDiff = worst;
        }
    }
    return success();
}

}  // namespace btflut::cli::eval
