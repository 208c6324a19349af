// A seeded mutation fuzzer of the impactgen command line. Each case is a
// problem file (an example of examples/problems/ or a random valid problem,
// then mutated in its JSON tree or its bytes) run through `solve --json` and
// one or two of formulas / explain / codegen in a child process. It checks
// what a user relies on whatever the input:
//   - no crash (signal or sanitizer report) and no hang (timeout);
//   - exit code 0, 1 (refusal) or 2 (usage error) only;
//   - a refusal is exactly one stderr line "impactgen: error: ..." besides
//     warnings, with nothing on stdout; a success has only warnings on stderr;
//   - no NUL or other raw control byte (besides \n and \t) in any output;
//   - an answer of `solve --json` satisfies the physics (physics_check.hpp);
//     `formulas --format json` prints JSON;
//   - a header from `codegen` has no #define/#include/#undef besides its own
//     IMPACTGEN_ macros, and every Nth one compiles with strict warnings; when the
//     problem has numbers only, that header is also built into a program whose
//     normal impulse and energy lost must equal solve's.
// Every violation is printed with its command and the case's file; the program
// exits 1 if there is any. Environment:
//   IMPACTGEN_SEED                master seed (default fixed)
//   IMPACTGEN_FUZZ_CASES          number of cases (default 300; 100 in a sanitizer build)
//   IMPACTGEN_FUZZ_CASE           run only this case number (reproduces one report; prints its file)
//   IMPACTGEN_FUZZ_TIMEOUT        seconds per run before SIGKILL (default 10)
//   IMPACTGEN_FUZZ_COMPILE_EVERY  compile every Nth successful codegen header (default 10; 0: never)
//   IMPACTGEN_FUZZ_SAVE           directory where the file of every failing case (or of IMPACTGEN_FUZZ_CASE) is written
#include "child.hpp"
#include "mutate.hpp"
#include "physics_check.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <unistd.h>

#ifndef IMPACTGEN_FUZZ_SANITIZED
#define IMPACTGEN_FUZZ_SANITIZED 0
#endif

namespace fs = std::filesystem;
using namespace impactgen::fuzz;

namespace {

struct config {
    unsigned long long seed = 20261123;
    long cases = IMPACTGEN_FUZZ_SANITIZED ? 100 : 300;
    long only_case = -1;
    double timeout = 10;
    long compile_every = 10;
    std::string save_dir;
    std::size_t max_reports = 40; ///< violations printed in full; the rest are counted
};

long long env_number(const char* name, long long fallback, long long lo, long long hi)
{
    const char* s = std::getenv(name);
    if (!s || !*s)
        return fallback;
    char* end = nullptr;
    long long v = std::strtoll(s, &end, 10);
    if (*end != '\0' || v < lo || v > hi) {
        std::fprintf(stderr, "fuzz_cli: %s=%s: expected an integer in [%lld, %lld]\n", name, s, lo, hi);
        std::exit(2);
    }
    return v;
}

config read_config()
{
    config c;
    c.seed = static_cast<unsigned long long>(env_number("IMPACTGEN_SEED", static_cast<long long>(c.seed), 0, LLONG_MAX));
    c.cases = static_cast<long>(env_number("IMPACTGEN_FUZZ_CASES", c.cases, 0, 100000000));
    c.only_case = static_cast<long>(env_number("IMPACTGEN_FUZZ_CASE", -1, -1, 100000000));
    c.timeout = static_cast<double>(env_number("IMPACTGEN_FUZZ_TIMEOUT", 10, 1, 86400));
    c.compile_every = static_cast<long>(env_number("IMPACTGEN_FUZZ_COMPILE_EVERY", 10, 0, 1000000));
    if (const char* s = std::getenv("IMPACTGEN_FUZZ_SAVE"))
        c.save_dir = s;
    return c;
}

// Printable ASCII as is; backslash, \n, \t and every other byte escaped.
std::string escaped(const std::string& s, std::size_t max_bytes)
{
    std::string r;
    char buf[8];
    for (std::size_t i = 0; i < s.size() && i < max_bytes; ++i) {
        unsigned char c = static_cast<unsigned char>(s[i]);
        if (c == '\\')
            r += "\\\\";
        else if (c == '\n')
            r += "\\n";
        else if (c == '\t')
            r += "\\t";
        else if (c >= 0x20 && c < 0x7f)
            r += static_cast<char>(c);
        else {
            std::snprintf(buf, sizeof buf, "\\x%02x", c);
            r += buf;
        }
    }
    if (s.size() > max_bytes)
        r += "... (" + std::to_string(s.size()) + " bytes in all)";
    return r;
}

std::vector<std::string> lines_of(const std::string& s)
{
    std::vector<std::string> r;
    std::size_t start = 0;
    while (start < s.size()) {
        std::size_t end = s.find('\n', start);
        if (end == std::string::npos) {
            r.push_back(s.substr(start));
            break;
        }
        r.push_back(s.substr(start, end - start));
        start = end + 1;
    }
    return r;
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// The first byte that a terminal, a file or a pipe reader should never get raw.
std::string control_byte(const std::string& s)
{
    for (std::size_t i = 0; i < s.size(); ++i) {
        unsigned char c = static_cast<unsigned char>(s[i]);
        if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "byte 0x%02x at offset %zu", c, i);
            return buf;
        }
    }
    return "";
}

std::string temp_file(const std::string& text, const std::string& suffix);

struct command {
    std::string label;              ///< the subcommand and options, for the report
    std::vector<std::string> args;  ///< after the file name
    std::string sub;
};

const std::vector<command>& other_commands()
{
    // codegen twice: its headers feed the compile check.
    static const std::vector<command> list = {
        {"formulas", {}, "formulas"},
        {"formulas --format json", {"--format", "json"}, "formulas"},
        {"formulas --format latex", {"--format", "latex"}, "formulas"},
        {"explain", {}, "explain"},
        {"explain --format latex", {"--format", "latex"}, "explain"},
        {"explain --format markdown", {"--format", "markdown"}, "explain"},
        {"codegen", {}, "codegen"},
        {"codegen", {}, "codegen"},
        {"solve", {}, "solve"},
    };
    return list;
}

struct violation_kind {
    const char* name;
    long count = 0;
};

enum kind_index { crash, hang, bad_exit, bad_message, bad_output, physics, false_refusal, compile_failure, kinds };

struct slowest {
    double seconds = 0;
    std::string what;
};

class fuzzer {
public:
    explicit fuzzer(const config& c) : cfg_(c) {}

    int run();

private:
    const config& cfg_;
    std::vector<std::pair<std::string, json>> examples_;
    violation_kind counts_[kinds] = {{"crashes"}, {"hangs"}, {"bad exit codes"}, {"bad messages"},
                                     {"bad output"}, {"physics failures"}, {"valid problems refused"},
                                     {"compile failures"}};
    long runs_ = 0, exit0_ = 0, refusals_ = 0, usage_ = 0, compiled_ = 0, codegen_ok_ = 0, cases_run_ = 0, generated_checked_ = 0;
    long answers_checked_ = 0;
    long reports_ = 0;
    slowest slowest_;
    std::map<std::string, slowest> slowest_by_label_;
    std::map<std::string, std::pair<long, long>> distinct_; ///< signature -> (count, first case)
    std::set<long> failing_cases_;

    // State of the case being run.
    long case_ = 0;
    std::string text_, file_, origin_, mutation_;
    std::string answer_; ///< this case's solve --json answer, when it had one
    void check_generated_numbers(const std::string& label, const std::string& header_path, const std::string& header);

    void load_examples();
    void one_case(long k);
    void run_command(const command& c, bool pristine_seed);
    void violation(kind_index kind, const std::string& label, const std::string& detail, const run_result* r,
                   const std::string& signature);
    void check_header(const std::string& label, const std::string& header);
};

void fuzzer::load_examples()
{
    std::vector<fs::path> files;
    // The one-contact examples and the systems of format version 3 (joints, contact lists, sequential).
    for (const char* sub : {"problems", "systems"})
        for (const auto& entry : fs::directory_iterator(fs::path(IMPACTGEN_SOURCE_DIR) / "examples" / sub))
            if (entry.path().extension() == ".json")
                files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
        std::ifstream in(f);
        std::stringstream ss;
        ss << in.rdbuf();
        examples_.emplace_back(f.filename().string(), json::parse(ss.str()));
    }
}

void fuzzer::violation(kind_index kind, const std::string& label, const std::string& detail, const run_result* r,
                       const std::string& signature)
{
    ++counts_[kind].count;
    auto& d = distinct_[std::string(counts_[kind].name) + " | " + label + " | " + signature];
    if (d.first++ == 0)
        d.second = case_;
    if (failing_cases_.insert(case_).second && !cfg_.save_dir.empty()) {
        std::ofstream out(fs::path(cfg_.save_dir) / ("case-" + std::to_string(case_) + ".json"), std::ios::binary);
        out << text_;
    }
    if (++reports_ > static_cast<long>(cfg_.max_reports)) {
        if (reports_ == static_cast<long>(cfg_.max_reports) + 1)
            std::cout << "fuzz_cli: further violations are counted, not printed\n";
        return;
    }
    std::cout << "\nFAIL [" << counts_[kind].name << "] case " << case_ << " (" << origin_ << "; " << mutation_
              << "; reproduce with IMPACTGEN_SEED=" << cfg_.seed << " IMPACTGEN_FUZZ_CASE=" << case_ << ")\n"
              << "  command: impactgen " << label << " FILE\n"
              << "  " << escaped(detail, 2000) << "\n";
    if (r) {
        std::cout << "  exit: " << (r->timed_out ? "timeout" : r->signal ? "signal " + std::to_string(r->signal) : std::to_string(r->exit_code))
                  << ", " << r->seconds << " s\n"
                  << "  stderr: " << escaped(r->err, 800) << "\n";
        if (kind != physics && kind != compile_failure)
            std::cout << "  stdout: " << escaped(r->out, 300) << "\n";
    }
    std::cout << "  file (" << text_.size() << " bytes): " << escaped(text_, 3000) << "\n";
}

// Strips what varies between instances of one finding: the file name, quoted
// names and values, numbers, the key a refusal names, a residual's size.
std::string signature_of(std::string s, const std::string& file)
{
    for (std::size_t at = s.find(file); !file.empty() && at != std::string::npos; at = s.find(file))
        s.replace(at, file.size(), "FILE");
    const std::string refusal = "impactgen: error: FILE: ";
    if (starts_with(s, refusal.c_str())) {
        std::size_t key_end = s.find(": ", refusal.size());
        if (key_end != std::string::npos)
            s = refusal + "KEY" + s.substr(key_end);
    }
    s = s.substr(0, s.find(": residual "));
    std::string r;
    bool quoted = false;
    for (char c : s) {
        if (c == '"') {
            r += quoted ? "\"" : "\"..";
            quoted = !quoted;
        } else if (quoted) {
            continue;
        } else if (c >= '0' && c <= '9') {
            if (r.empty() || r.back() != '#')
                r += '#';
        } else {
            r += c;
        }
    }
    return r.substr(0, 160);
}

void fuzzer::check_header(const std::string& label, const std::string& header)
{
    for (const std::string& line : lines_of(header)) {
        std::size_t k = line.find_first_not_of(" \t");
        if (k == std::string::npos || line[k] != '#')
            continue;
        std::string directive = line.substr(k + 1);
        directive.erase(0, directive.find_first_not_of(" \t"));
        // Its own guarded macros, and standard headers (<cmath> for sqrt), are the only ones allowed.
        bool own_macro = starts_with(line, "#define IMPACTGEN_");
        bool system_include = starts_with(directive, "include") &&
                              directive.find_first_not_of(" \t", 7) != std::string::npos &&
                              directive[directive.find_first_not_of(" \t", 7)] == '<';
        if ((starts_with(directive, "define") && !own_macro) || (starts_with(directive, "include") && !system_include) ||
            starts_with(directive, "undef"))
            violation(compile_failure, label, "the header has a preprocessor line of its own: " + line, nullptr,
                      "preprocessor line in the header");
    }
    if (cfg_.compile_every == 0 || (codegen_ok_ - 1) % cfg_.compile_every != 0)
        return;
    // The header is compiled as a header (its #pragma once would be an error in
    // a main file), included twice: its include guard must hold.
    const std::string path = temp_file(header, ".hpp");
    const std::string main_file = "#include \"" + path + "\"\n#include \"" + path + "\"\n";
    run_limits lim;
    lim.timeout_seconds = std::max(120.0, cfg_.timeout);
    run_result r = run_child({IMPACTGEN_CXX, "-std=c++17", "-fsyntax-only", "-Wall", "-Wextra", "-Wpedantic", "-Werror",
                              "-x", "c++", "-"},
                             main_file, lim);
    if (r.exit_code == 0 && !r.timed_out)
        check_generated_numbers(label, path, header);
    ::unlink(path.c_str());
    ++compiled_;
    if (r.timed_out || r.signal != 0 || r.exit_code != 0) {
        std::vector<std::string> err = lines_of(r.err);
        std::string first = err.empty() ? "no message" : err.front();
        std::string shown;
        for (std::size_t i = 0; i < err.size() && i < 8; ++i)
            shown += err[i] + "\n";
        violation(compile_failure, label, "the header does not compile:\n" + shown, nullptr,
                  signature_of(first.substr(first.find(' ') == std::string::npos ? 0 : first.find(' ')), ""));
    }
}

// A header of a problem with numbers only (no inputs): compiled, run in double,
// its normal impulse and energy lost must be solve's (1e-9 relative: both are
// the exact value rounded to double, through at most a few hundred operations).
void fuzzer::check_generated_numbers(const std::string& label, const std::string& header_path, const std::string& header)
{
    const std::string marker = "_input_count = 0;";
    std::size_t at = header.find(marker);
    if (answer_.empty() || at == std::string::npos)
        return;
    std::size_t start = header.rfind("inline constexpr int ", at);
    if (start == std::string::npos)
        return;
    start += std::string("inline constexpr int ").size();
    const std::string name = header.substr(start, at - start);
    json answer;
    try {
        answer = json::parse(answer_);
    } catch (const std::exception&) {
        return;
    }
    if (!answer.contains("normal_impulse") || !answer["normal_impulse"].is_number())
        return;
    const std::string main_text = "#include \"" + header_path + "\"\n#include <cstdio>\nint main()\n{\n    using namespace impactgen::generated;\n    " +
                                  name + "_result<double> r{};\n    impact_status s = " + name +
                                  "<double>(r);\n    std::printf(\"%d %.17g %.17g\\n\", static_cast<int>(s), r.normal_impulse, r.energy_lost);\n}\n";
    const std::string main_path = temp_file(main_text, ".cpp");
    const std::string exe = main_path + ".exe";
    run_limits lim;
    lim.timeout_seconds = std::max(120.0, cfg_.timeout);
    run_result built = run_child({IMPACTGEN_CXX, "-std=c++17", "-O1", main_path, "-o", exe}, "", lim);
    ::unlink(main_path.c_str());
    if (built.exit_code != 0) {
        violation(compile_failure, label, "the header does not compile into a program:\n" + built.err, nullptr, "header program does not build");
        return;
    }
    run_result ran = run_child({exe}, "", lim);
    ::unlink(exe.c_str());
    int status = -1;
    double N = 0, lost = 0;
    if (ran.exit_code != 0 || std::sscanf(ran.out.c_str(), "%d %lf %lf", &status, &N, &lost) != 3) {
        violation(physics, label, "the generated program failed: " + ran.out + ran.err, nullptr, "generated program failed");
        return;
    }
    const double N_ref = answer["normal_impulse"].get<double>();
    const double lost_ref = answer["kinetic_energy"]["lost"].get<double>();
    const double scale_N = std::max(1e-300, std::fabs(N_ref)), scale_T = std::max(1e-300, std::fabs(answer["kinetic_energy"]["before"].get<double>()) + std::fabs(lost_ref));
    ++generated_checked_;
    if (status != 0 || std::fabs(N - N_ref) > 1e-9 * scale_N || std::fabs(lost - lost_ref) > 1e-9 * scale_T)
        violation(physics, label,
                  "generated code disagrees with solve: status " + std::to_string(status) + ", N " + std::to_string(N) + " vs " +
                      std::to_string(N_ref) + ", energy lost " + std::to_string(lost) + " vs " + std::to_string(lost_ref),
                  nullptr, "generated code disagrees with solve");
}

void fuzzer::run_command(const command& c, bool pristine_seed)
{
    std::vector<std::string> argv = {IMPACTGEN_CLI, c.sub};
    argv.push_back(file_);
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    run_limits lim;
    lim.timeout_seconds = cfg_.timeout;
    lim.memory_mb = IMPACTGEN_FUZZ_SANITIZED ? 0 : 4096; // a runaway child must not take the machine
    run_result r = run_child(argv, "", lim);
    ++runs_;
    if (r.seconds > slowest_.seconds)
        slowest_ = {r.seconds, "impactgen " + c.label + " FILE, case " + std::to_string(case_)};
    slowest& s = slowest_by_label_[c.label];
    if (r.seconds > s.seconds)
        s = {r.seconds, "case " + std::to_string(case_)};

    const std::vector<std::string> err = lines_of(r.err);
    const std::string first_err = err.empty() ? "" : err.front();
    if (r.timed_out) {
        violation(hang, c.label, "no answer within " + std::to_string(static_cast<int>(cfg_.timeout)) + " s (killed)", &r, "timeout");
        return;
    }
    // impactgen's own watchdog (--time-limit, 10 s by default) ends a run that
    // would hang: a hang all the same, whichever of the two deadlines comes first.
    if (r.exit_code == 1 && r.err.find("time budget") != std::string::npos) {
        violation(hang, c.label, "stopped by impactgen's own time budget", &r, "time budget exhausted");
        return;
    }
    if (r.signal != 0) {
        violation(crash, c.label, std::string("killed by signal ") + std::to_string(r.signal) + " (" + strsignal(r.signal) + ")", &r,
                  "signal " + std::to_string(r.signal) + ": " + signature_of(first_err, file_));
        return;
    }
    for (const char* marker : {"ERROR: AddressSanitizer", "ERROR: LeakSanitizer", "runtime error:"}) {
        std::size_t at = r.err.find(marker);
        if (at != std::string::npos) {
            std::size_t eol = r.err.find('\n', at);
            violation(crash, c.label, "sanitizer report", &r, signature_of(r.err.substr(at, eol - at), file_));
            return;
        }
    }
    if (r.exit_code != 0 && r.exit_code != 1 && r.exit_code != 2) {
        violation(bad_exit, c.label, "exit code " + std::to_string(r.exit_code), &r,
                  "exit " + std::to_string(r.exit_code) + ": " + signature_of(first_err, file_));
        return;
    }
    r.exit_code == 0 ? ++exit0_ : r.exit_code == 1 ? ++refusals_ : ++usage_;

    for (const auto* stream : {&r.out, &r.err}) {
        std::string bad = control_byte(*stream);
        if (!bad.empty())
            violation(bad_output, c.label, std::string(stream == &r.out ? "stdout" : "stderr") + " has the raw control " + bad,
                      &r, std::string(stream == &r.out ? "stdout" : "stderr") + " control byte");
    }
    std::vector<std::string> non_warning;
    for (const std::string& line : err)
        if (!starts_with(line, "impactgen: warning:"))
            non_warning.push_back(line);
    const bool terminated = r.err.empty() || r.err.back() == '\n';
    if (r.exit_code != 0) {
        std::string why;
        if (r.exit_code == 1 && non_warning.size() != 1)
            why = "exit 1 with " + std::to_string(non_warning.size()) + " stderr lines besides warnings (expected 1)";
        else if (r.exit_code == 1 && !starts_with(non_warning.front(), "impactgen: error: "))
            why = "the message does not start with \"impactgen: error: \"";
        else if (non_warning.empty())
            why = "exit " + std::to_string(r.exit_code) + " without a message";
        else if (!terminated)
            why = "the message does not end with a newline";
        else if (r.exit_code == 1 && !r.out.empty())
            why = "exit 1 with output on stdout";
        if (!why.empty())
            violation(bad_message, c.label, why, &r, why);
        // A generated problem with numbers only is valid by construction: solve must answer it.
        if (pristine_seed && c.label == "solve --json" && r.exit_code == 1)
            violation(false_refusal, c.label, "a valid problem (not mutated) refused", &r, signature_of(first_err, file_));
        return;
    }
    if (!non_warning.empty() || !terminated)
        violation(bad_message, c.label, "exit 0 with stderr lines that are not warnings", &r, "exit 0 with non-warning stderr");
    if (r.out.empty())
        violation(bad_output, c.label, "exit 0 with nothing on stdout", &r, "exit 0, empty stdout");
    if (c.label == "solve --json") {
        answer_ = r.out;
        ++answers_checked_;
        std::vector<std::string> failures = check_answer(text_, r.out);
        if (!failures.empty()) {
            std::string all;
            for (const std::string& f : failures)
                all += (all.empty() ? "" : "\n  ") + f;
            violation(physics, c.label, all + "\n  answer: " + r.out, &r, signature_of(failures.front(), file_));
        }
    } else if (c.label == "formulas --format json") {
        try {
            json j = json::parse(r.out);
            // A system's formulas are its candidates (format version 3).
            const bool system = j.is_object() && j.contains("candidates") && j["candidates"].is_array();
            if (!system && (!j.is_object() || !j.contains("bodies") || !j.contains("normal_impulse")))
                violation(bad_output, c.label, "the formulas object lacks bodies or normal_impulse", &r, "formulas json lacks keys");
        } catch (const std::exception& e) {
            violation(bad_output, c.label, std::string("stdout is not JSON: ") + e.what(), &r, "formulas json does not parse");
        }
    } else if (c.sub == "codegen") {
        ++codegen_ok_;
        check_header(c.label, r.out);
    }
}

std::string temp_file(const std::string& text, const std::string& suffix)
{
    const char* tmp = std::getenv("TMPDIR");
    std::string path = std::string(tmp && *tmp ? tmp : "/tmp") + "/impactgen-fuzz-XXXXXX" + suffix;
    std::vector<char> buf(path.begin(), path.end());
    buf.push_back('\0');
    int fd = mkstemps(buf.data(), static_cast<int>(suffix.size()));
    if (fd < 0) {
        std::perror("fuzz_cli: mkstemps");
        std::exit(2);
    }
    std::size_t done = 0;
    while (done < text.size()) {
        ssize_t w = ::write(fd, text.data() + done, text.size() - done);
        if (w <= 0) {
            std::perror("fuzz_cli: write");
            std::exit(2);
        }
        done += static_cast<std::size_t>(w);
    }
    ::close(fd);
    return buf.data();
}

// A whole file that is no problem at all.
std::string hostile_file(engine& rng)
{
    switch (std::uniform_int_distribution<int>(0, 6)(rng)) {
    case 0: return "";
    case 1: return "null";
    case 2: return std::string(100000, '[') + std::string(100000, ']');
    case 3: return "{\"dimension\": 2, \"restitution\": \"" + std::string(70000, '1') + "\"}";
    case 4: return std::string("{\"dimension\"\0: 2}", 17);
    case 5: {
        std::string s(std::uniform_int_distribution<int>(1, 4000)(rng), ' ');
        for (char& c : s)
            c = static_cast<char>(std::uniform_int_distribution<int>(0, 255)(rng));
        return s;
    }
    default: return "\xef\xbb\xbf{}";
    }
}

void fuzzer::one_case(long k)
{
    case_ = k;
    ++cases_run_;
    answer_.clear();
    // Every case has its own engine: one case is reproduced without the others.
    std::seed_seq seq{static_cast<unsigned>(cfg_.seed), static_cast<unsigned>(cfg_.seed >> 32), static_cast<unsigned>(k),
                      static_cast<unsigned>(static_cast<unsigned long long>(k) >> 32)};
    engine rng(seq);
    std::uniform_real_distribution<double> unit(0, 1);

    json tree;
    bool numeric_seed = false;
    if (!examples_.empty() && unit(rng) < 0.2) {
        const auto& ex = examples_[std::uniform_int_distribution<std::size_t>(0, examples_.size() - 1)(rng)];
        origin_ = ex.first;
        tree = ex.second;
    } else {
        origin_ = "generated";
        tree = random_problem(rng, &numeric_seed);
    }
    const double mode = unit(rng);
    bool pristine = false;
    auto count = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    if (mode < 0.2) {
        mutation_ = "not mutated";
        text_ = serialise(tree, rng);
        pristine = numeric_seed;
    } else if (mode < 0.85) {
        mutation_ = mutate_tree(tree, rng, count(1, 3));
        text_ = serialise(tree, rng);
    } else if (mode < 0.98) {
        mutation_ = mutate_tree(tree, rng, count(0, 1));
        text_ = serialise(tree, rng);
        mutation_ += (mutation_.empty() ? "bytes: " : "; bytes: ") + mutate_bytes(text_, rng, count(1, 4));
    } else {
        mutation_ = "hostile file";
        text_ = hostile_file(rng);
    }
    file_ = temp_file(text_, ".json");
    if (cfg_.only_case >= 0) { // reproducing one case: show it, and keep it when asked to
        std::cout << "case " << k << " (" << origin_ << "; " << mutation_ << "): " << escaped(text_, 100000) << "\n";
        if (!cfg_.save_dir.empty())
            std::ofstream(fs::path(cfg_.save_dir) / ("case-" + std::to_string(k) + ".json"), std::ios::binary) << text_;
    }

    std::vector<command> chosen = {{"solve --json", {"--json"}, "solve"}};
    const auto& others = other_commands();
    const int n_others = count(1, 2);
    while (static_cast<int>(chosen.size()) < 1 + n_others) {
        const command& c = others[std::uniform_int_distribution<std::size_t>(0, others.size() - 1)(rng)];
        bool seen = false;
        for (const command& x : chosen)
            seen = seen || x.label == c.label;
        if (!seen)
            chosen.push_back(c);
    }
    for (const command& c : chosen)
        run_command(c, pristine);
    ::unlink(file_.c_str());
}

int fuzzer::run()
{
    const auto start = std::chrono::steady_clock::now();
    load_examples();
    if (cfg_.only_case >= 0)
        one_case(cfg_.only_case);
    else
        for (long k = 0; k < cfg_.cases; ++k)
            one_case(k);
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    long violations = 0;
    for (const auto& c : counts_)
        violations += c.count;
    if (!distinct_.empty()) {
        std::cout << "\nDistinct findings (count, first case):\n";
        for (const auto& d : distinct_)
            std::cout << "  " << d.second.first << " x  " << escaped(d.first, 300) << "  (case " << d.second.second << ")\n";
    }
    std::cout << "\nSlowest run per subcommand:";
    for (const auto& s : slowest_by_label_)
        std::printf("\n  %-26s %.3f s (%s)", s.first.c_str(), s.second.seconds, s.second.what.c_str());
    std::printf("\nfuzz_cli: seed %llu: %ld cases, %ld runs: %ld exit 0, %ld refusals (exit 1), %ld usage errors (exit 2); ",
                cfg_.seed, cases_run_, runs_, exit0_, refusals_, usage_);
    for (int k = 0; k < kinds; ++k)
        std::printf("%ld %s, ", counts_[k].count, counts_[k].name);
    std::printf("%ld answers checked, %ld headers compiled (%ld run against solve); slowest run %.3f s (%s); %.1f s in all\n",
                answers_checked_, compiled_, generated_checked_, slowest_.seconds,
                slowest_.what.c_str(), total);
    return violations == 0 ? 0 : 1;
}

} // namespace

int main()
{
    config cfg = read_config();
    fuzzer f(cfg);
    return f.run();
}
