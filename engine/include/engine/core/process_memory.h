#pragma once
// This process's memory as the kernel counts it (/proc/self/status on Linux): what is resident in
// RAM now, its peak, and the address space. On a software GL driver (llvmpipe) "GPU" buffers live
// in this memory too. Fields are 0 where the system does not report them.
#include <cstdint>

namespace engine {

struct ProcessMemory {
    std::uint64_t resident_bytes = 0;       // VmRSS
    std::uint64_t peak_resident_bytes = 0;  // VmHWM
    std::uint64_t virtual_bytes = 0;        // VmSize
};

ProcessMemory process_memory();

}  // namespace engine
