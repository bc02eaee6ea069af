// actionstring CLI — subcommand entry points.
#pragma once

namespace actionstring {
namespace cli {

/// `actionstring demo`: streams a synthetic performance through the runtime.
int run_demo(int argc, char** argv);

/// `actionstring info FILE`: joints, frames, duration, rate and bounds of a motion file.
int run_info(int argc, char** argv);

/// `actionstring train --clips LIST --out MODEL`: trains and writes a model artifact.
int run_train(int argc, char** argv);

/// `actionstring codegen MODEL --out HEADER`: the constexpr header of a model.
int run_codegen(int argc, char** argv);

/// `actionstring eval --model MODEL --clips LIST`: clip recognition beside baselines.
int run_eval(int argc, char** argv);

/// `actionstring annotate --model MODEL FILE`: the label timeline of a recording.
int run_annotate(int argc, char** argv);

/// `actionstring view FILE --model MODEL --out PAGE`: an HTML page to watch a recording with its labels.
int run_view(int argc, char** argv);

/// `actionstring stream-table --clips LIST --out HEADER`: a recorded stream as constexpr tables.
int run_stream_table(int argc, char** argv);
/// `actionstring interval-list`: a continuous dataset's timeline as a clip list with intervals.
int run_interval_list(int argc, char** argv);

}  // namespace cli
}  // namespace actionstring
