// Golden files of `formulas` (text, every named class and every symbolic example) and
// `solve` (text, every numeric example problem): the command-line output byte for byte, the same in every
// process (GiNaC's term order changes from run to run; the printers must not).
// IMPACTGEN_REGENERATE_GOLDEN=1 (or `make regenerate-golden-explain`) rewrites them.
#include "symbolic/named_classes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace {

std::string command_output(const std::string& args, int& status)
{
    std::string out;
    // From the source tree, files by relative path: `formulas` names its source in the output.
    FILE* f = popen(("cd '" + std::string(IMPACTGEN_SOURCE_DIR) + "' && " + std::string(IMPACTGEN_CLI) + " " + args + " 2>/dev/null").c_str(), "r");
    if (!f) {
        status = -1;
        return out;
    }
    std::array<char, 4096> buf;
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0)
        out.append(buf.data(), n);
    status = pclose(f);
    return out;
}

std::string read_text(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void compare_or_regenerate(const std::string& args, const fs::path& golden)
{
    int status = 0;
    const std::string out = command_output(args, status);
    ASSERT_EQ(status, 0) << "impactgen " << args;
    if (std::getenv("IMPACTGEN_REGENERATE_GOLDEN")) {
        fs::create_directories(golden.parent_path());
        if (!fs::exists(golden) || read_text(golden) != out)
            std::ofstream(golden, std::ios::binary) << out;
        return;
    }
    ASSERT_TRUE(fs::exists(golden)) << golden << " is missing: run make regenerate-golden-explain";
    EXPECT_EQ(read_text(golden), out) << golden << " differs from `impactgen " << args
                                      << "`: review the change, then make regenerate-golden-explain";
}

std::vector<std::string> every_class()
{
    std::vector<std::string> names;
    for (const impactgen::named_class& c : impactgen::named_classes())
        names.push_back(c.name);
    for (const impactgen::named_class& c : impactgen::friction_classes())
        names.push_back(c.name);
    return names;
}

std::vector<fs::path> example_problems()
{
    std::vector<fs::path> files;
    for (const char* dir : {"examples/problems", "examples/friction"})
        for (const auto& entry : fs::directory_iterator(fs::path(IMPACTGEN_SOURCE_DIR) / dir))
            if (entry.path().extension() == ".json")
                files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

TEST(OutputGolden, FormulasOfEveryClass)
{
    const fs::path dir = fs::path(IMPACTGEN_GOLDEN_DIR) / "formulas";
    for (const std::string& c : every_class())
        compare_or_regenerate("formulas " + c, dir / (c + ".txt"));
}

TEST(OutputGolden, SolveOfEveryExample)
{
    const fs::path dir = fs::path(IMPACTGEN_GOLDEN_DIR) / "solve";
    const std::vector<fs::path> files = example_problems();
    ASSERT_GE(files.size(), 8u);
    for (const fs::path& f : files) { // the text names no path: the golden holds wherever the tree is
        const std::string rel = fs::relative(f, IMPACTGEN_SOURCE_DIR).generic_string();
        int status = 0;
        command_output("solve " + rel, status);
        if (status == 0)
            compare_or_regenerate("solve " + rel, dir / (f.stem().string() + ".txt"));
        else // an example with symbols: its formulas
            compare_or_regenerate("formulas " + rel, dir.parent_path() / "formulas" / (f.stem().string() + ".txt"));
    }
}

} // namespace
