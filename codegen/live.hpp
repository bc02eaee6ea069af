// `actionstring annotate --live`: frames as they arrive, labels and events out
// the moment they are known.
#pragma once

#include "actionstring/annotator.hpp"
#include "io/clip.hpp"
#include "model/model_data.hpp"

namespace actionstring {
namespace cli {

/// Where live frames come from: standard input, or UDP datagrams on the loopback interface.
struct LiveSource {
    int udp_port = 0;           ///< 0: standard input.
    double idle_timeout_s = 0;  ///< UDP: stop after this long without a datagram (0: never).
};

/// Reads a joint CSV header and then one frame per line (a datagram may hold
/// several lines), maps the joints to the model's by name, runs the annotator
/// per frame and prints JSON lines at once (flushed): each change of the
/// settled label and each action event; a malformed line is skipped and
/// counted, never fatal. At the end of the input (or the idle timeout) the
/// stream is flushed. Returns the exit status.
int run_live(const host::ModelData& model, const AnnotatorConfig& config, const host::ReadOptions& read,
             const LiveSource& source);

}  // namespace cli
}  // namespace actionstring
