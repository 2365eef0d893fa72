// What a model will take in memory, told before it is allocated: a model too large for the machine is
// refused with both figures instead of running the machine out of memory (or into swap) hours later.
// The figures are the arrays' sizes per particle and per grid node; the check compares what is about
// to be allocated with the memory the system says is available now.
#pragma once

#include <cstdint>
#include <string>

namespace seismpm {

// The memory the system can give without swapping (MemAvailable), in bytes; 0 when it cannot be told.
std::uint64_t available_memory();

// "1.4 GiB", "730 MiB", "12 KiB".
std::string format_bytes(std::uint64_t bytes);

// Throws InputError when `need` bytes exceed the available memory: "<what> needs about N, more than the
// M of memory available now; <how to allow it>". Nothing is checked when the available memory is unknown.
void check_memory(std::uint64_t need, const std::string& what);

}  // namespace seismpm
