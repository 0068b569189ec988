#include "core/predict/predictor_fit.h"

#include "core/predict/kinds.h"

namespace btflut {

namespace {

// The kinds fitted to the images (kinds.cpp): the first that knows the name.
const FitKind* kindNamed(const std::string& name) {
    for (const KindEntry& entry : kindEntries())
        if (entry.fit && entry.fit->named(name)) return entry.fit;
    return nullptr;
}

}  // namespace

bool PredictorFit::trains() const { return kind().trains; }

bool PredictorFit::takesViews() const { return kind().takesViews; }

std::optional<Result<FitPointer>> predictorFitNamed(const std::string& name) {
    const FitKind* kind = kindNamed(name);
    if (!kind) return std::nullopt;
    return kind->named(name);
}

bool predictorTrains(const std::string& name) {
    const FitKind* kind = kindNamed(name);
    return kind && kind->trains;
}

bool predictorTakesViews(const std::string& name) {
    const FitKind* kind = kindNamed(name);
    return kind && kind->takesViews;
}

std::vector<FitCandidate> fitCandidates(const CandidateBounds& bounds) {
    std::vector<FitCandidate> out;
    for (const KindEntry& entry : kindEntries()) {
        if (!entry.fit) continue;
        std::vector<FitCandidate> own = entry.fit->candidates(bounds);
        out.insert(out.end(), std::make_move_iterator(own.begin()), std::make_move_iterator(own.end()));
    }
    return out;
}

}  // namespace btflut
