// Big blocks on transparent huge pages, for the tm-<verb> programs where that was measured to pay (the
// list, and why not everywhere, in tools/CMakeLists.txt). This file replaces the global operator new and
// delete of the programs it is linked into; the libraries and the other programs keep the default.
//
// Why: the surface steps hold a 1 mm head's millions of vertices and triangles in arrays of tens to
// hundreds of MiB, made and dropped many times (a copy of the positions per smoothing step, the checker's
// tables). Each new block is faulted in page by page, and 4 KiB faults are dear on these virtual machines
// (tm-check-surface on the head: 19.7 s with them, 7.3 s without). The whole 2 MiB pages inside each block
// of 2 MiB or more are therefore marked MADV_HUGEPAGE, so they fault in 2 MiB at a time where the kernel
// allows transparent huge pages (Debian's default "madvise" mode); elsewhere the advice is refused and
// nothing changes. Aligning the blocks to 2 MiB (aligned_alloc) was as fast but cost 40% more peak memory.
// Figures in bench/HISTORY.md (the surface chain's sixth round). Same results, byte for byte: only where memory
// comes from changes.
//
// Not under AddressSanitizer, whose own operator new checks that blocks are freed the way they were made.
#if !defined(__SANITIZE_ADDRESS__)

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t huge_page = std::size_t{2} << 20;

/// A block of `size` bytes, or nullptr; the whole huge pages inside it advised.
void* try_allocate(std::size_t size)
{
    void* block = std::malloc(size == 0 ? 1 : size);
    if (block != nullptr && size >= huge_page) {
        const auto start = (reinterpret_cast<std::uintptr_t>(block) + huge_page - 1) / huge_page * huge_page;
        const auto end = (reinterpret_cast<std::uintptr_t>(block) + size) / huge_page * huge_page;
        if (end > start) // refused (EINVAL) without THP: harmless
            madvise(reinterpret_cast<void*>(start), end - start, MADV_HUGEPAGE);
    }
    return block;
}

} // namespace

// The replaceable pair; libstdc++'s array, nothrow and sized forms call these. Failure follows the
// standard: call the new-handler while there is one, then throw std::bad_alloc.
void* operator new(std::size_t size)
{
    for (;;) {
        if (void* block = try_allocate(size)) return block;
        const std::new_handler handler = std::get_new_handler();
        if (handler == nullptr) throw std::bad_alloc();
        handler();
    }
}

void operator delete(void* block) noexcept { std::free(block); }

void operator delete(void* block, std::size_t) noexcept { std::free(block); }

#endif
