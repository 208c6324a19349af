// Exercise sheets (issue 25) from the command line: `impactgen exercises` writes the folder;
// `impactgen solve --json` of every problems/NN.json is answers/NN.json byte for byte; the
// Moodle quiz parses (python3's XML parser, check_quiz.py) and every question's answer is the
// answer file's; sheet.tex compiles with pdflatex with 0 overfull boxes; sheet.html opens in
// headless Chromium with one figure per exercise; bad options are refused with one line.
// pdflatex, python3 and Chromium missing: the test says so loudly and is skipped.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;

namespace
{

std::string run(const std::string &cmd, int &status)
{
    std::string out;
    FILE *pipe = ::popen(cmd.c_str(), "r");
    if (!pipe) {
        status = -1;
        return out;
    }
    std::array<char, 4096> buf;
    while (std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe))
        out.append(buf.data(), n);
    const int rc = ::pclose(pipe);
    status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    return out;
}

std::string shell_quoted(const std::string &s)
{
    return "'" + s + "'";
}

bool have(const std::string &tool)
{
    int status = 0;
    run("command -v " + tool + " >/dev/null 2>&1", status);
    return status == 0;
}

std::string read_text(const fs::path &p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::size_t count(const std::string &s, const std::string &what)
{
    std::size_t n = 0;
    for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + what.size()))
        ++n;
    return n;
}

/// A sheet written by the command line into a fresh folder.
fs::path sheet(const std::string &what, const std::string &options)
{
    const fs::path dir = fs::temp_directory_path() / ("impactgen-exercises-" + std::to_string(::getpid()) + "-" +
                                                      std::to_string(std::hash<std::string>{}(what + options)));
    fs::remove_all(dir);
    int status = 0;
    const std::string out =
        run(shell_quoted(IMPACTGEN_CLI) + " exercises " + shell_quoted(what) + " " + options + " --out " + shell_quoted(dir.string()) + " 2>&1",
            status);
    EXPECT_EQ(status, 0) << out;
    return dir;
}

std::string hinged_rod()
{
    return std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/hinged-rod.json";
}

} // namespace

TEST(ExercisesCli, AnswersAreSolveOfTheProblemFiles)
{
    for (const auto &[what, options] : {std::pair<std::string, std::string>{hinged_rod(), "--count 4 --seed 2"},
                                        {"ball-floor-friction", "--count 3 --seed 5 --regime stick"},
                                        {"planar", "--count 3 --seed 8"},
                                        {std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/compass-gait.json",
                                         "--count 3 --seed 3"}}) {
        SCOPED_TRACE(what);
        const fs::path dir = sheet(what, options);
        std::size_t n = 0;
        for (const auto &entry : fs::directory_iterator(dir / "problems")) {
            int status = 0;
            const std::string solved =
                run(shell_quoted(IMPACTGEN_CLI) + " solve --json " + shell_quoted(entry.path().string()), status);
            ASSERT_EQ(status, 0) << entry.path();
            EXPECT_EQ(solved, read_text(dir / "answers" / entry.path().filename())) << entry.path();
            ++n;
        }
        EXPECT_GE(n, 3u);
        fs::remove_all(dir);
    }
}

TEST(ExercisesCli, SameSeedSameFolder)
{
    const fs::path a = sheet(hinged_rod(), "--count 2 --seed 9"), b = sheet(hinged_rod(), "--seed 9 --count 2");
    for (const char *name : {"sheet.tex", "sheet.html", "quiz.xml", "problems/02.json", "solutions/02.tex"})
        EXPECT_EQ(read_text(a / name), read_text(b / name)) << name;
    fs::remove_all(a);
    fs::remove_all(b);
}

TEST(ExercisesCli, MoodleQuizParsesAndEveryAnswerIsTheAnswerFiles)
{
    if (!have("python3"))
        GTEST_SKIP() << "\n*** python3 NOT FOUND: the Moodle XML of exercises is NOT CHECKED ***\n";
    // a system too: contacts, a joint and their impulses in the answer file (compass gait)
    for (const std::string &what :
         {std::string("planar-friction"), std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/compass-gait.json"}) {
        SCOPED_TRACE(what);
        const fs::path dir = sheet(what, "--count 3 --seed 4");
        int status = 0;
        const std::string out =
            run("python3 " + shell_quoted(std::string(IMPACTGEN_SOURCE_DIR) + "/tests/exercises/check_quiz.py") + " " +
                    shell_quoted(dir.string()) + " 2>&1",
                status);
        EXPECT_EQ(status, 0) << out;
        ASSERT_EQ(out.rfind("ok ", 0), 0u) << out;
        EXPECT_GE(std::stoi(out.substr(3)), 3 * 5); // velocities, spins, impulses, energy of each
        fs::remove_all(dir);
    }
}

TEST(ExercisesCli, LatexSheetCompilesWithoutOverfullBoxes)
{
    if (!have("pdflatex"))
        GTEST_SKIP() << "\n*** pdflatex NOT FOUND: the LaTeX sheet of exercises is NOT COMPILED ***\n";
    // hostile-names.json: body names with LaTeX's special characters ("50% a_b#{x}", "~^\\end{document}")
    for (const std::string &what : {hinged_rod(), std::string("ball-floor-friction"), std::string("noncentral-3d"),
                                    std::string(IMPACTGEN_SOURCE_DIR) + "/tests/explain/hostile-names.json",
                                    std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/three-balls-sequential.json"}) {
        SCOPED_TRACE(what);
        const fs::path dir = sheet(what, "--count 10 --seed 1");
        int status = 0;
        const std::string log = run("cd " + shell_quoted(dir.string()) +
                                        " && pdflatex -interaction=nonstopmode -halt-on-error sheet.tex 2>&1",
                                    status);
        EXPECT_EQ(status, 0) << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
        EXPECT_TRUE(fs::exists(dir / "sheet.pdf"));
        EXPECT_EQ(count(read_text(dir / "sheet.log"), "Overfull"), 0u);
        // a worked solution compiles too
        run("cd " + shell_quoted((dir / "solutions").string()) + " && pdflatex -interaction=nonstopmode -halt-on-error 01.tex 2>&1",
            status);
        EXPECT_EQ(status, 0);
        fs::remove_all(dir);
    }
}

TEST(ExercisesCli, HtmlSheetOpensInChromium)
{
    int status = 0;
    std::string browser = run("command -v chromium || command -v chromium-browser", status);
    browser = browser.substr(0, browser.find('\n'));
    if (status != 0 || browser.empty())
        GTEST_SKIP() << "\n*** chromium NOT FOUND: the HTML sheet of exercises is NOT CHECKED in a browser ***\n";
    const fs::path dir = sheet("ball-floor-friction", "--count 4 --seed 6");
    const std::string dom =
        run("timeout 60 " + shell_quoted(browser) +
                " --headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run --disable-extensions"
                " --disable-background-networking --user-data-dir=" +
                shell_quoted((dir / "profile").string()) + " --window-size=1000,1400 --screenshot=" +
                shell_quoted((dir / "sheet.png").string()) + " --dump-dom " + shell_quoted("file://" + (dir / "sheet.html").string()) +
                " 2>/dev/null",
            status);
    ASSERT_EQ(status, 0);
    ASSERT_NE(dom.find("</html>"), std::string::npos);
    EXPECT_EQ(count(dom, "<svg"), 4u); // a figure per exercise
    EXPECT_EQ(count(dom, "<section class=\"exercise\""), 4u);
    EXPECT_EQ(count(dom, "<parsererror"), 0u);
    EXPECT_NE(dom.find("Answers"), std::string::npos);
    EXPECT_GT(fs::file_size(dir / "sheet.png"), 10000u); // a rendered page, not a blank one
    fs::remove_all(dir);
}

TEST(ExercisesCli, BadOptionsAreRefusedWithOneLine)
{
    const fs::path file = fs::temp_directory_path() / ("impactgen-exercises-file-" + std::to_string(::getpid()));
    std::ofstream(file) << "x";
    const std::string cli = shell_quoted(IMPACTGEN_CLI) + " exercises ";
    for (const std::string &args :
         {hinged_rod() + " --count 0 --out /tmp/impactgen-never", std::string("no-such-class --out /tmp/impactgen-never"),
          hinged_rod() + " --count 2 --out " + shell_quoted((file / "sub").string()),
          hinged_rod() + " --count 2 --regime stick --out /tmp/impactgen-never",
          std::string("planar-friction --regime smooth --out /tmp/impactgen-never"),
          hinged_rod() + " --regime bounce --out /tmp/impactgen-never", hinged_rod()}) {
        SCOPED_TRACE(args);
        int status = 0;
        const std::string err = run(cli + args + " 2>&1 >/dev/null", status);
        EXPECT_NE(status, 0);
        EXPECT_EQ(count(err, "\n"), 1u) << err;
        EXPECT_EQ(err.rfind("impactgen: error: ", 0), 0u) << err;
    }
    EXPECT_FALSE(fs::exists("/tmp/impactgen-never"));
    fs::remove(file);
}
