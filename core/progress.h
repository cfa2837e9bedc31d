// Progress and log messages: the library calls these; a tool decides how to show them (stderr).
// Library code never prints.
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace tissuemesh {

enum class LogLevel { debug, info, warning };

/// Callbacks a library function reports through. A default-constructed Progress is silent.
/// `stage` is the short step name that prefixes log lines ("extract", "decimate").
class Progress {
public:
    using FractionCallback = std::function<void(std::string_view stage, double fraction)>;
    using MessageCallback = std::function<void(LogLevel level, std::string_view stage, std::string_view text)>;

    Progress() = default;
    Progress(FractionCallback on_fraction, MessageCallback on_message)
        : on_fraction_(std::move(on_fraction)), on_message_(std::move(on_message))
    {
    }

    /// Reports that `fraction` (0..1) of the stage is done.
    void update(std::string_view stage, double fraction) const
    {
        if (on_fraction_) on_fraction_(stage, fraction);
    }
    void debug(std::string_view stage, std::string_view text) const { message(LogLevel::debug, stage, text); }
    void info(std::string_view stage, std::string_view text) const { message(LogLevel::info, stage, text); }
    void warn(std::string_view stage, std::string_view text) const { message(LogLevel::warning, stage, text); }
    void message(LogLevel level, std::string_view stage, std::string_view text) const
    {
        if (on_message_) on_message_(level, stage, text);
    }

private:
    FractionCallback on_fraction_;
    MessageCallback on_message_;
};

/// Reports progress of a loop of `total` steps at most `updates` times, for hot loops:
///     ProgressTicker ticker(progress, "extract", slices);
///     for (...) { ...; ticker.step(); }
class ProgressTicker {
public:
    ProgressTicker(const Progress& progress, std::string stage, std::size_t total, std::size_t updates = 20);
    void step(std::size_t count = 1);

private:
    const Progress& progress_;
    std::string stage_;
    std::size_t total_;
    std::size_t done_ = 0;
    std::size_t next_report_ = 0;
    std::size_t interval_;
};

} // namespace tissuemesh
