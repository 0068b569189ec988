// btflut render: the GL renderer, headless (OSMesa or EGL).
#include <iostream>
#include <memory>

#include "cli/cli.h"
#include "core/bank_file.h"
#include "gl/context.h"
#include "gl/native_renderer.h"

namespace btflut::cli {

namespace {

struct RenderOptions {
    std::string bank;
    std::string light;
    std::string view = "0,0";
    std::string output;
    std::string backend = "auto";
    bool native = false;
    bool verbose = false;
    int depth = 8;
    bool noDither = false;
};

Status runRender(const RenderOptions& o) {
    if (Status s = requireExtension(o.output, {"png"}, "output"); !s) return s;
    if (!o.native) return Error{"give --native: the frontal quad at the reference image's resolution is the "
                                "mode this version renders"};
    Result<GlBackend> backend = parseGlBackend(o.backend);
    if (!backend) return Error{backend.error()};
    Result<BankAtDirection> query = loadBankAt(o.bank, o.light, o.view);
    if (!query) return Error{query.error()};
    LutBank& bank = query->bank;
    Result<std::unique_ptr<HeadlessContext>> context = createHeadlessContext(*backend);
    if (!context) return Error{context.error()};
    if (o.verbose) std::cout << "context: " << (*context)->description() << "\n";
    Result<Image> image = renderNative(bank, query->light, query->view, !o.noDither);
    if (!image) return Error{o.bank + ": " + image.error()};
    if (Status s = savePng(*image, o.output, o.depth); !s) return s;
    std::cout << "wrote " << o.output << " (" << image->width << "x" << image->height << ")\n";
    return success();
}

}  // namespace

void addRenderCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* app = root.add_subcommand("render", "Render with OpenGL, headless (OSMesa or EGL)");
    app->add_option("BANK", o->bank, "M.btflut")->required();
    app->add_option("--light", o->light, "light direction THETA,PHI in degrees")->required();
    app->add_option("--view", o->view, "view direction THETA,PHI in degrees")->capture_default_str();
    app->add_flag("--native", o->native, "the frontal quad at the reference image's own resolution");
    app->add_option("-o,--output", o->output, "out.png")->required();
    app->add_option("--backend", o->backend, "auto (EGL, then OSMesa), osmesa or egl")->capture_default_str();
    app->add_flag("-v,--verbose", o->verbose, "print the context's backend and driver");
    addLutImageOptions(*app, o->depth, o->noDither);
    commands.push_back({app, [o] { return runRender(*o); }});
}

}  // namespace btflut::cli
