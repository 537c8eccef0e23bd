// Slot storage behind the typed handles, shared by every backend. get() on a destroyed or never
// created handle throws rhi::Error naming the handle type and what went wrong, so a use-after-
// destroy is caught at the call that made it instead of corrupting a reused slot.
#pragma once

#include "rhi/Error.h"
#include "rhi/Handle.h"

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace lpv::rhi {

template <typename Tag, typename T> class HandlePool {
public:
    using HandleType = Handle<Tag>;

    HandleType insert(T value) {
        uint32_t index;
        if (!free_.empty()) {
            index = free_.back();
            free_.pop_back();
        } else {
            if (slots_.size() >= 0xffffu) throw Error(std::string("out of ") + Tag::kName + " slots (65535)");
            index = uint32_t(slots_.size());
            slots_.emplace_back();
        }
        Slot& slot = slots_[index];
        slot.value.emplace(std::move(value));
        return HandleType::make(index, slot.generation);
    }

    T& get(HandleType h) { return *slots_[check(h)].value; }
    const T& get(HandleType h) const { return *slots_[check(h)].value; }

    bool contains(HandleType h) const {
        return h.valid() && h.index() < slots_.size() && slots_[h.index()].value &&
               slots_[h.index()].generation == h.generation();
    }

    // Removes the entry and returns it; the slot's generation moves on so old handles go stale.
    T remove(HandleType h) {
        Slot& slot = slots_[check(h)];
        T value = std::move(*slot.value);
        slot.value.reset();
        slot.generation = slot.generation == 0xffffu ? 1u : slot.generation + 1u;
        free_.push_back(h.index());
        return value;
    }

    template <typename F> void forEach(F&& f) {
        for (uint32_t i = 0; i < slots_.size(); ++i)
            if (slots_[i].value) f(HandleType::make(i, slots_[i].generation), *slots_[i].value);
    }

    size_t size() const { return slots_.size() - free_.size(); }

private:
    struct Slot {
        std::optional<T> value;
        uint32_t generation = 1;
    };

    uint32_t check(HandleType h) const {
        if (!h.valid()) throw Error(std::string("use of a null ") + Tag::kName);
        if (h.index() >= slots_.size())
            throw Error(std::string("use of an unknown ") + Tag::kName + " (slot " +
                        std::to_string(h.index()) + " was never created)");
        const Slot& slot = slots_[h.index()];
        if (!slot.value || slot.generation != h.generation())
            throw Error(std::string("use of a stale ") + Tag::kName + " (slot " + std::to_string(h.index()) +
                        ", generation " + std::to_string(h.generation()) + "): the resource was destroyed");
        return h.index();
    }

    std::vector<Slot> slots_;
    std::vector<uint32_t> free_;
};

} // namespace lpv::rhi
