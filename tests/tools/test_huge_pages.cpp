// tools/huge_pages.cpp, linked into this test program as into the tm-<verb> programs that use it: big
// blocks get the kernel's huge-page advice, and failure still throws std::bad_alloc.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <limits>
#include <memory>
#include <new>
#include <sstream>
#include <string>

namespace {

bool kernel_has_transparent_huge_pages()
{
    std::ifstream setting("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string text;
    std::getline(setting, text);
    return setting && text.find("[never]") == std::string::npos;
}

/// The VmFlags of the mapping that holds `address`, from /proc/self/smaps ("" when none does).
std::string mapping_flags(const void* address)
{
    const auto where = reinterpret_cast<std::uintptr_t>(address);
    std::ifstream smaps("/proc/self/smaps");
    bool inside = false;
    for (std::string line; std::getline(smaps, line);) {
        std::uintptr_t low = 0, high = 0;
        char dash = 0;
        std::istringstream range(line);
        if (range >> std::hex >> low >> dash >> high && dash == '-') {
            inside = low <= where && where < high;
            continue;
        }
        if (inside && line.rfind("VmFlags:", 0) == 0) return line;
    }
    return "";
}

bool advised_huge(const void* address) { return mapping_flags(address).find(" hg") != std::string::npos; }

bool sanitized()
{
#if defined(__SANITIZE_ADDRESS__)
    return true;
#else
    return false;
#endif
}

TEST(HugePages, BigBlocksAreAdvised)
{
    if (sanitized()) GTEST_SKIP() << "the replacement is left out under AddressSanitizer";
    if (!kernel_has_transparent_huge_pages()) GTEST_SKIP() << "this kernel has no transparent huge pages";
    constexpr std::size_t mib = std::size_t{1} << 20;
    const auto big = std::make_unique<char[]>(64 * mib);
    // The middle of the block lies on a whole 2 MiB page of it, which must carry the advice.
    EXPECT_TRUE(advised_huge(big.get() + 32 * mib)) << mapping_flags(big.get() + 32 * mib);
    big[64 * mib - 1] = 1; // the block is usable to its end
}

// Sizes the compiler cannot see, so that it neither warns about them nor drops the calls.
volatile std::size_t beyond_memory = std::size_t{1} << 62;
volatile std::size_t beyond_address_space = std::numeric_limits<std::size_t>::max() - 16;

TEST(HugePages, ImpossibleBlocksStillThrowBadAlloc)
{
    // AddressSanitizer's own operator new stops the program on such sizes instead (allocation-size-too-big).
    if (sanitized()) GTEST_SKIP() << "the replacement is left out under AddressSanitizer";
    EXPECT_THROW(static_cast<void>(::operator new(beyond_address_space)), std::bad_alloc);
    EXPECT_THROW(static_cast<void>(::operator new(beyond_memory)), std::bad_alloc);
}

TEST(HugePages, TheNewHandlerIsCalledBeforeGivingUp)
{
    if (sanitized()) GTEST_SKIP() << "the replacement is left out under AddressSanitizer";
    static int calls = 0;
    calls = 0;
    const std::new_handler previous = std::set_new_handler([] {
        if (++calls == 2) std::set_new_handler(nullptr);
    });
    EXPECT_THROW(static_cast<void>(::operator new(beyond_memory)), std::bad_alloc);
    std::set_new_handler(previous);
    EXPECT_EQ(calls, 2);
}

} // namespace
