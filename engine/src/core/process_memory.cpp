#include "engine/core/process_memory.h"

#include <cstdio>

namespace engine {

ProcessMemory process_memory() {
    ProcessMemory m;
    std::FILE* status = std::fopen("/proc/self/status", "r");
    if (status == nullptr) return m;
    char line[256];
    while (std::fgets(line, sizeof line, status) != nullptr) {
        unsigned long long kib = 0;
        if (std::sscanf(line, "VmRSS: %llu kB", &kib) == 1)
            m.resident_bytes = kib * 1024;
        else if (std::sscanf(line, "VmHWM: %llu kB", &kib) == 1)
            m.peak_resident_bytes = kib * 1024;
        else if (std::sscanf(line, "VmSize: %llu kB", &kib) == 1)
            m.virtual_bytes = kib * 1024;
    }
    std::fclose(status);
    return m;
}

}  // namespace engine
