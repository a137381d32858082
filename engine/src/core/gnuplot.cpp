// gnuplot helpers (engine/core/gnuplot.h).
#include "engine/core/gnuplot.h"

#include <cstdio>
#include <cstdlib>

#include "engine/core/error.h"

namespace engine {

std::string gnuplot_png_terminal() {
    FILE* pipe = popen("gnuplot -e 'set terminal' 2>&1", "r");
    if (!pipe) return {};
    std::string text;
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipe)) text += buffer;
    if (pclose(pipe) != 0) return {};
    if (text.find("pngcairo") != std::string::npos) return "pngcairo font 'sans,10'";
    if (text.find(" png ") != std::string::npos) return "png";
    return {};
}

std::string shell_quoted(const std::filesystem::path& path) {
    std::string out = "'";
    for (const char c : path.string()) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

void run_gnuplot(const std::filesystem::path& folder, const std::string& script, const std::string& log) {
    const std::string command =
        "cd " + shell_quoted(folder) + " && gnuplot " + shell_quoted(script) + " > " + shell_quoted(log) + " 2>&1";
    if (std::system(command.c_str()) != 0)
        fail((folder / script).string() + ": gnuplot failed; its messages are in " + (folder / log).string());
}

}  // namespace engine
