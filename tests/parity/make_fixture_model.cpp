// Trains a model on synthetic toy clips with the real training pipeline and
// writes its artifact: the fixture of the header/artifact parity test, made
// at build time so the test needs no dataset.
#include <cstdio>
#include <string>

#include "model/artifact.hpp"
#include "model/header.hpp"
#include "io/stream.hpp"
#include "toy/toy.hpp"
#include "run/classify.hpp"
#include "run/encode.hpp"
#include "train/gmm_em.hpp"
#include "train/pca.hpp"
#include "train/pipeline.hpp"

int main(int argc, char** argv) {
    const bool without_gmm = argc == 3 && std::string(argv[2]) == "--no-gmm";
    if (argc != 2 && !without_gmm) {
        std::fprintf(stderr, "usage: make_fixture_model OUT.model [--no-gmm]\n");
        return 2;
    }
    using namespace actionstring::host;
    try {
        ToyWorld world = make_toy_world();
        TrainingOptions options;
        options.components = 6;
        options.pca_dim = 8;
        options.string_rate_hz = 10.0;
        options.sigma = 4.0;
        options.covariance_floor = 1e-3;
        options.normalization = actionstring::LengthNormalization::path;
        options.sigma = 0.3;
        options.neighbours = 3;
        if (without_gmm) {  // the paper's "PCA only" characters: the tree on projected poses,
            // here with bone-length scaling and the velocity too, so the header and the
            // artifact are compared on every input stage
            options.components = 0;
            options.scale_mode = actionstring::ScaleMode::bone_lengths;
            options.velocity_weight = 1.0;
            options.velocity_span_s = 0.3;
            options.epsilon = 0.5;
            options.sigma = 0.05;
        }
        ModelData model = train_model(toy_clips(world, 6, 100), options);
        save_model(model, argv[1]);
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "make_fixture_model: %s\n", error.what());
        return 1;
    }
}
