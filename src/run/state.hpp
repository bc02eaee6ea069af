// actionstring host library — a runtime state object with exactly the
// storage its model needs, allocated on the host.
#pragma once

#include <cstddef>
#include <memory>
#include <new>

#include "actionstring/model.hpp"
#include "actionstring/status.hpp"
#include "actionstring/storage.hpp"

namespace actionstring {
namespace host {

/// A state object (Annotator, StringEncoder, WindowMatcher, ActionSegmenter,
/// MotionRing) and its storage. init() allocates required_bytes() for the
/// model and settings, so no model is too large; the state's own per-frame
/// code never allocates. The model must outlive it (or its next init()).
template <class State>
class Stateful {
public:
    /// Sizes the storage for the model and settings and initialises the state
    /// in it. `settings` are what State::init() takes before the storage.
    template <class... Settings>
    Status init(const ModelView& model, const Settings&... settings) {
        bytes_ = State::required_bytes(model, settings...);
        // Nothing can hold it: let the state say why (a setting, the model, or its size).
        if (bytes_ == unsatisfiable_bytes) return state_.init(model, settings..., nullptr, 0);
        storage_.reset(bytes_ == 0
                           ? nullptr
                           : static_cast<unsigned char*>(::operator new (bytes_, std::align_val_t{state_alignment})));
        return state_.init(model, settings..., storage_.get(), bytes_);
    }

    State& operator*() noexcept { return state_; }
    const State& operator*() const noexcept { return state_; }
    State* operator->() noexcept { return &state_; }
    const State* operator->() const noexcept { return &state_; }
    /// Bytes of storage the state holds.
    std::size_t storage_bytes() const noexcept { return bytes_; }

private:
    struct Release {
        void operator()(unsigned char* p) const noexcept { ::operator delete (p, std::align_val_t{state_alignment}); }
    };
    State state_;
    std::unique_ptr<unsigned char, Release> storage_;
    std::size_t bytes_ = 0;
};

}  // namespace host
}  // namespace actionstring
