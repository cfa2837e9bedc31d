// VertexQueue: a priority queue holding at most one entry per vertex (an indexed binary heap), for
// decimation. A queue with lazy deletion grows by every re-queued vertex (about seven per collapse:
// tens of millions of stale entries on a head, and cache misses on every pop); this one stays at the
// number of vertices. Pops come in the order of (cost, v, w), as a lazy queue would give them. Four
// children per node (one cache line of entries): half the levels of a binary heap, which on millions of
// vertices means half the cache misses per update.
#pragma once

#include <algorithm>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

namespace tissuemesh::surface::detail {

class VertexQueue {
public:
    struct Entry {
        double cost = 0;
        std::uint32_t v = 0; ///< the vertex (the key: one entry per vertex)
        std::uint32_t w = 0; ///< payload, part of the order
        bool operator<(const Entry& other) const
        {
            return std::tie(cost, v, w) < std::tie(other.cost, other.v, other.w);
        }
    };

    bool empty() const { return heap_.empty(); }
    const Entry& top() const { return heap_.front(); }

    /// v's entry, or nullptr when v is not queued.
    const Entry* find(std::uint32_t v) const
    {
        return v < where_.size() && where_[v] != none ? &heap_[where_[v]] : nullptr;
    }

    /// Sets v's entry (adding or replacing it).
    void set(const Entry& entry)
    {
        if (entry.v >= where_.size()) where_.resize(static_cast<std::size_t>(entry.v) + 1, none);
        std::size_t i = where_[entry.v];
        if (where_[entry.v] == none) {
            i = heap_.size();
            heap_.push_back(entry);
        } else {
            heap_[i] = entry;
        }
        where_[entry.v] = static_cast<std::uint32_t>(i);
        i = up(i);
        down(i);
    }

    /// Removes v's entry, if any.
    void erase(std::uint32_t v)
    {
        if (v >= where_.size() || where_[v] == none) return;
        const std::size_t i = where_[v];
        where_[v] = none;
        const Entry last = heap_.back();
        heap_.pop_back();
        if (i == heap_.size()) return;
        heap_[i] = last;
        where_[last.v] = static_cast<std::uint32_t>(i);
        down(up(i));
    }

    void pop() { erase(heap_.front().v); }

private:
    static constexpr std::uint32_t none = static_cast<std::uint32_t>(-1);
    static constexpr std::size_t arity = 4;

    void place(std::size_t i, const Entry& entry)
    {
        heap_[i] = entry;
        where_[entry.v] = static_cast<std::uint32_t>(i);
    }
    std::size_t up(std::size_t i)
    {
        const Entry entry = heap_[i];
        while (i > 0 && entry < heap_[(i - 1) / arity]) {
            place(i, heap_[(i - 1) / arity]);
            i = (i - 1) / arity;
        }
        place(i, entry);
        return i;
    }
    void down(std::size_t i)
    {
        const Entry entry = heap_[i];
        for (;;) {
            const std::size_t first = arity * i + 1;
            if (first >= heap_.size()) break;
            std::size_t child = first;
            for (std::size_t c = first + 1; c < std::min(first + arity, heap_.size()); ++c)
                if (heap_[c] < heap_[child]) child = c;
            if (!(heap_[child] < entry)) break;
            place(i, heap_[child]);
            i = child;
        }
        place(i, entry);
    }

    std::vector<Entry> heap_;
    std::vector<std::uint32_t> where_; ///< per vertex: its index in heap_, or none
};

} // namespace tissuemesh::surface::detail
