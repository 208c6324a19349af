// The public entry points of code generation that are not the writer (writer.cpp holds
// generate()): the default function name, writing a header only when it changed.
#include "codegen.hpp"
#include "runtime.hpp"
#include "text.hpp"

#include "names/escape.hpp"
#include "names/identifier.hpp"
#include "symbolic/decide.hpp"
#include "symbolic/response.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

namespace impactgen::codegen
{
using namespace GiNaC;

std::string default_function_name(const std::string &stem)
{
    std::string name = names::mangle(stem);
    while (name.size() > 1 && name.back() == '_') // "int" mangles to int_; int__result would be reserved
        name.pop_back();
    return names::is_safe_identifier(name) && !reserved().count(name) ? name : name + "_impact";
}

bool write_if_changed(const std::string &path, const std::string &text)
{
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
        throw input_error(names::display_text(path) +
                          ": not a regular file (the header is written only to a regular file or "
                          "standard output)");
    if (std::filesystem::exists(status)) {
        std::ifstream in(path, std::ios::binary);
        if (in) {
            std::stringstream ss;
            ss << in.rdbuf();
            if (ss.str() == text)
                return false;
        }
    }
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out)
        throw input_error("cannot write " + names::display_text(path));
    out << text;
    out.close();
    if (!out)
        throw input_error("cannot write " + names::display_text(path));
    return true;
}

} // namespace impactgen::codegen
