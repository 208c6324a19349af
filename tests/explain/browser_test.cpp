// explain --format html in a real browser: every named class (smooth, with friction, and the
// named systems) and every example problem of examples/problems, examples/friction, examples/laws
// and examples/systems is written by the command line, opened in
// headless Chromium, and
//   - the DOM after parsing (--dump-dom) has <math> elements, one id="eq-N"
//     per numbered equation, the figure's <svg> when the document has a figure
//     block, no <merror> and no <parsererror>;
//   - no displayed equation is wider than the page's column (measured by a script
//     added to a copy of the page: the page itself has none);
//   - the screenshot (--screenshot, 1000x1400) is not blank: larger than the
//     screenshot of a blank page taken in the same test and, when zlib is
//     there to decode the PNG, with many more non-white pixels than it.
// Without chromium every test is skipped with a loud message. Every chromium
// call runs under `timeout 60`.
#include "print/explain.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/named_systems.hpp"

#include "latex_tools.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <unistd.h>

#ifdef IMPACTGEN_HAVE_ZLIB
#include <zlib.h>
#endif

using namespace impactgen;
using namespace impactgen::print;
namespace fs = std::filesystem;
using latex_tools::read_file;
using latex_tools::run;

namespace {

std::string quoted(const std::string& s) { return "'" + s + "'"; } // our own paths: no quote in them

// The browser: $IMPACTGEN_CHROMIUM, else chromium on the PATH; "" when there is none.
std::string chromium()
{
    if (const char* env = std::getenv("IMPACTGEN_CHROMIUM"))
        return env;
    int status = 0;
    std::string path = run("command -v chromium || command -v chromium-browser", status);
    while (!path.empty() && (path.back() == '\n' || path.back() == '\r'))
        path.pop_back();
    return status == 0 ? path.substr(0, path.find('\n')) : "";
}

// Headless Chromium with its own profile directory (pages may run in parallel).
std::string browser_command(const std::string& browser, const fs::path& dir, const std::string& what)
{
    return "timeout 60 " + quoted(browser) +
           " --headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run --disable-extensions"
           " --disable-background-networking --user-data-dir=" +
           quoted((dir / "profile").string()) + " " + what;
}

/// A decoded PNG: the number of pixels and how many are not (nearly) white.
struct png_stats {
    bool decoded = false;
    std::size_t pixels = 0, dark = 0;
};

#ifdef IMPACTGEN_HAVE_ZLIB
std::uint32_t be32(const std::string& s, std::size_t at)
{
    return (std::uint32_t(static_cast<unsigned char>(s[at])) << 24) | (std::uint32_t(static_cast<unsigned char>(s[at + 1])) << 16) |
           (std::uint32_t(static_cast<unsigned char>(s[at + 2])) << 8) | std::uint32_t(static_cast<unsigned char>(s[at + 3]));
}

// 8-bit grey, grey+alpha, RGB or RGBA, not interlaced (what Chromium writes).
png_stats decode(const std::string& png)
{
    png_stats st;
    if (png.size() < 33 || png.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0)
        return st;
    std::uint32_t width = 0, height = 0;
    int depth = 0, colour = 0, interlace = 0;
    std::string idat;
    for (std::size_t at = 8; at + 12 <= png.size();) {
        const std::uint32_t len = be32(png, at);
        const std::string type = png.substr(at + 4, 4);
        if (at + 12 + len > png.size())
            return st;
        if (type == "IHDR") {
            width = be32(png, at + 8);
            height = be32(png, at + 12);
            depth = static_cast<unsigned char>(png[at + 16]);
            colour = static_cast<unsigned char>(png[at + 17]);
            interlace = static_cast<unsigned char>(png[at + 20]);
        } else if (type == "IDAT") {
            idat += png.substr(at + 8, len);
        }
        at += 12 + len;
    }
    const int channels = colour == 0 ? 1 : colour == 4 ? 2 : colour == 2 ? 3 : colour == 6 ? 4 : 0;
    if (depth != 8 || channels == 0 || interlace != 0 || width == 0 || height == 0 || width > 20000 || height > 20000)
        return st;
    const std::size_t stride = std::size_t(width) * channels;
    std::vector<unsigned char> raw(std::size_t(height) * (stride + 1));
    uLongf raw_len = static_cast<uLongf>(raw.size());
    if (uncompress(raw.data(), &raw_len, reinterpret_cast<const Bytef*>(idat.data()), static_cast<uLong>(idat.size())) != Z_OK ||
        raw_len != raw.size())
        return st;
    // Undo the per-row filters (none, sub, up, average, Paeth).
    std::vector<unsigned char> prev(stride, 0), cur(stride);
    for (std::uint32_t y = 0; y < height; ++y) {
        const unsigned char* in = &raw[std::size_t(y) * (stride + 1)];
        const int filter = in[0];
        for (std::size_t x = 0; x < stride; ++x) {
            const int a = x >= std::size_t(channels) ? cur[x - channels] : 0, b = prev[x],
                      c = x >= std::size_t(channels) ? prev[x - channels] : 0;
            int predicted = 0;
            switch (filter) {
            case 0: break;
            case 1: predicted = a; break;
            case 2: predicted = b; break;
            case 3: predicted = (a + b) / 2; break;
            case 4: {
                const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
                predicted = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
                break;
            }
            default: return st;
            }
            cur[x] = static_cast<unsigned char>(in[1 + x] + predicted);
        }
        for (std::uint32_t x = 0; x < width; ++x) {
            const unsigned char* px = &cur[std::size_t(x) * channels];
            const int grey_channels = channels <= 2 ? 1 : 3;
            bool dark = false;
            for (int k = 0; k < grey_channels; ++k)
                dark = dark || px[k] < 200;
            st.dark += dark ? 1 : 0;
        }
        std::swap(prev, cur);
    }
    st.pixels = std::size_t(width) * height;
    st.decoded = true;
    return st;
}
#else
png_stats decode(const std::string&) { return {}; }
#endif

struct page {
    std::string name; ///< the test's name
    std::string what; ///< the argument of `impactgen explain`, relative to the source tree
};

// The named classes (smooth, with friction, and the named systems), examples/problems/*.json,
// examples/friction/*.json, examples/laws/*.json and examples/systems/*.json; names only: the
// documents are built in the test that needs one. A page is named as its class or its file's
// stem; a file whose stem is a class's name (examples/systems/compass-gait.json, the worked example
// of the class compass-gait) is named with its folder in front: systems-compass-gait.
std::vector<page> pages()
{
    std::vector<page> out;
    for (const auto* list : {&named_classes(), &friction_classes(), &system_classes()})
        for (const named_class& c : *list)
            out.push_back({c.name, c.name});
    const std::size_t classes = out.size();
    for (const char* dir : {"examples/problems", "examples/friction", "examples/laws", "examples/systems"}) {
        std::vector<fs::path> files;
        for (const auto& entry : fs::directory_iterator(fs::path(IMPACTGEN_SOURCE_DIR) / dir))
            if (entry.path().extension() == ".json")
                files.push_back(entry.path());
        std::sort(files.begin(), files.end());
        for (const fs::path& f : files) {
            std::string name = f.stem().string();
            if (std::any_of(out.begin(), out.begin() + static_cast<long>(classes),
                            [&](const page& pg) { return pg.name == name; }))
                name = fs::path(dir).filename().string() + "-" + name;
            out.push_back({name, std::string(dir) + "/" + f.filename().string()});
        }
    }
    return out;
}

std::vector<std::string> page_names()
{
    std::vector<std::string> names;
    for (const page& p : pages())
        names.push_back(p.name);
    return names;
}

// The document the command line prints for that page (smooth, with friction, or a system).
document document_of(const page& pg)
{
    const bool named = find_named_class(pg.what) != nullptr;
    problem p = named ? find_named_class(pg.what)->build()
                      : read_problem(read_file(fs::path(IMPACTGEN_SOURCE_DIR) / pg.what), pg.what);
    derivation d = derive(p);
    if (p.is_system())
        return explain_system(d);
    worked_example ex;
    bool has = named && notes_example(pg.what, ex);
    return explain(d, solve_impact(d), has ? &ex : nullptr);
}

std::size_t count(const std::string& s, const std::string& part)
{
    std::size_t n = 0;
    for (std::size_t k = s.find(part); k != std::string::npos; k = s.find(part, k + 1))
        ++n;
    return n;
}

// The anchor of a tag, as explain_html writes it: (3) is eq-3, (e = 0) is eq-e-=-0.
std::string eq_id(const std::string& tag)
{
    std::string id = "eq-";
    for (char c : tag)
        if (!std::isspace(static_cast<unsigned char>(c)))
            id += c;
        else if (id.back() != '-')
            id += '-';
    return id;
}

// Text as the DOM serializer writes it: & < > escaped, quotes as they are.
std::string dom_text(const std::string& s)
{
    std::string out;
    for (char c : s)
        out += c == '&' ? "&amp;" : c == '<' ? "&lt;" : c == '>' ? "&gt;" : std::string(1, c);
    return out;
}

class Browser : public ::testing::TestWithParam<std::string> {};

} // namespace

// The list of pages: every named class of every kind (as `impactgen list` has them) and every
// example file is a page, each under its own name.
TEST(BrowserPages, EveryNamedClassAndExampleFileIsAPage)
{
    const std::vector<page> all = pages();
    std::set<std::string> names, what;
    for (const page& p : all) {
        EXPECT_TRUE(names.insert(p.name).second) << "two pages named " << p.name;
        what.insert(p.what);
    }
    for (const auto* list : {&named_classes(), &friction_classes(), &system_classes()}) {
        for (const named_class& c : *list) {
            EXPECT_EQ(what.count(c.name), 1u) << "the class " << c.name << " is not a page";
        }
    }
    for (const char* c : {"compass-gait", "three-balls", "double-pendulum-struck", "two-corner-landing"})
        EXPECT_EQ(what.count(c), 1u) << c;
    for (const char* dir : {"examples/problems", "examples/friction", "examples/laws", "examples/systems"})
        for (const auto& entry : fs::directory_iterator(fs::path(IMPACTGEN_SOURCE_DIR) / dir)) {
            if (entry.path().extension() == ".json") {
                EXPECT_EQ(what.count(std::string(dir) + "/" + entry.path().filename().string()), 1u) << entry.path();
            }
        }
}

TEST_P(Browser, ParsesAndRendersThePage)
{
    const std::string browser = chromium();
    if (browser.empty())
        GTEST_SKIP() << "\n*** chromium NOT FOUND: the HTML output of explain is NOT CHECKED in a browser. "
                        "Install it with: apt-get install --no-install-recommends chromium "
                        "(scripts/install-deps.sh --tests) ***\n";
    const std::vector<page> all = pages();
    const page& pg = *std::find_if(all.begin(), all.end(), [](const page& p) { return p.name == GetParam(); });
    const document doc = document_of(pg);
    const fs::path dir = fs::temp_directory_path() / ("impactgen-browser-" + pg.name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);

    // The page as the command line writes it.
    int status = 0;
    run("cd " + quoted(IMPACTGEN_SOURCE_DIR) + " && timeout 60 " + quoted(IMPACTGEN_CLI) + " explain " + quoted(pg.what) +
            " --format html > " + quoted((dir / "page.html").string()),
        status);
    ASSERT_EQ(status, 0) << "impactgen explain " << pg.what << " --format html";
    std::ofstream(dir / "blank.html") << "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>blank</title></head><body></body></html>\n";
    // The page has no script of its own; the browser opens a copy with one measuring script
    // added at the end (it only writes an attribute): every displayed equation whose
    // MathML is wider than its column (it would scroll on screen and be cut in print).
    const std::string html = read_file(dir / "page.html");
    EXPECT_EQ(count(html, "<script"), 0u);
    const std::size_t body_end = html.rfind("</body>");
    ASSERT_NE(body_end, std::string::npos);
    std::ofstream(dir / "measured.html")
        << html.substr(0, body_end)
        << "<script>(function () { var bad = []; var all = document.querySelectorAll('.eq > math');"
           " for (var i = 0; i < all.length; ++i) { var m = all[i];"
           " if (m.scrollWidth > m.clientWidth + 2) bad.push((m.parentNode.id || 'row ' + i) + ' ' + m.scrollWidth + ' px in '"
           " + m.clientWidth + ' px'); }"
           " document.body.setAttribute('data-overflow', bad.length + (bad.length ? ': ' + bad.join('; ') : '')); })();</script>"
        << html.substr(body_end);
    const std::string url = "file://" + (dir / "measured.html").string();

    // The DOM after parsing, and the screenshot of the page, from one start of the browser.
    const std::string dom = run(browser_command(browser, dir,
                                                "--window-size=1000,1400 --screenshot=" + quoted((dir / "page.png").string()) +
                                                    " --dump-dom " + quoted(url)) +
                                    " 2>/dev/null",
                                status);
    ASSERT_EQ(status, 0) << "chromium --dump-dom --screenshot failed or timed out";
    ASSERT_NE(dom.find("</html>"), std::string::npos) << dom.substr(0, 500);
    EXPECT_GT(count(dom, "<math"), 10u);
    EXPECT_GT(count(dom, "<math display=\"block\">"), 3u);
    EXPECT_EQ(count(dom, "<merror"), 0u);
    EXPECT_EQ(count(dom, "<parsererror"), 0u);
    EXPECT_EQ(count(dom, "<script"), 1u); // the measuring one
    const std::size_t overflow = dom.find("data-overflow=\"");
    ASSERT_NE(overflow, std::string::npos) << "the measuring script did not run";
    const std::string measured = dom.substr(overflow + 15, dom.find('"', overflow + 15) - overflow - 15);
    EXPECT_EQ(measured, "0") << "displayed equations wider than the column (1000 px window): " << measured;
    std::set<std::string> tags;
    bool figure = false;
    for (const section& sec : doc.sections)
        for (const block& b : sec.blocks) {
            figure = figure || b.k == block::figure;
            for (const math_row& r : b.math)
                if (!r.tag.empty())
                    tags.insert(r.tag);
        }
    EXPECT_FALSE(tags.empty());
    for (const std::string& t : tags) {
        EXPECT_EQ(count(dom, "id=\"" + dom_text(eq_id(t)) + "\""), 1u) << "equation (" << t << ")";
        EXPECT_NE(dom.find("<span class=\"tag\">(" + dom_text(t) + ")</span>"), std::string::npos) << t;
    }
    if (figure) {
        EXPECT_NE(dom.find("<svg"), std::string::npos) << "the document has a figure block: its <svg> is not in the DOM";
    }

    // The screenshot of the page (above) and one of a blank page, the same size.
    auto screenshot = [&](const std::string& html, const std::string& png) {
        int st = 0;
        run(browser_command(browser, dir, "--window-size=1000,1400 --screenshot=" + quoted((dir / png).string()) + " " +
                                              quoted("file://" + (dir / html).string())) +
                " > /dev/null 2>&1",
            st);
        EXPECT_EQ(st, 0) << "chromium --screenshot failed or timed out (" << html << ")";
        return read_file(dir / png);
    };
    const std::string shot = read_file(dir / "page.png"), blank = screenshot("blank.html", "blank.png");
    ASSERT_FALSE(blank.empty());
    ASSERT_FALSE(shot.empty());
    EXPECT_GT(shot.size(), blank.size() * 5) << "the screenshot is hardly larger than a blank page's";
    const png_stats page_px = decode(shot), blank_px = decode(blank);
    if (page_px.decoded && blank_px.decoded) {
        std::cout << "[ browser ] " << pg.name << ": screenshot " << shot.size() << " bytes, "
                  << 100.0 * double(page_px.dark) / double(page_px.pixels) << "% of the pixels not white (blank page: "
                  << blank.size() << " bytes, " << blank_px.dark << " pixels)\n";
        EXPECT_EQ(page_px.pixels, 1000u * 1400u);
        EXPECT_LT(blank_px.dark, blank_px.pixels / 1000) << "the blank page is not blank: the decoder is wrong";
        EXPECT_GT(page_px.dark, page_px.pixels / 200) << "fewer than 0.5% of the pixels are not white";
    } else {
        std::cout << "[ browser ] PNG not decoded (built without zlib): only the sizes were compared\n";
    }
    if (!::testing::Test::HasFailure())
        fs::remove_all(dir);
    else
        std::cout << "[ browser ] files kept in " << dir << "\n";
}

INSTANTIATE_TEST_SUITE_P(Pages, Browser, ::testing::ValuesIn(page_names()), [](const auto& info) {
    std::string n = info.param;
    for (char& c : n)
        if (!std::isalnum(static_cast<unsigned char>(c)))
            c = '_';
    return n;
});
