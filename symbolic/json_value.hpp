// A JSON tree that keeps every number as the text it was written in, so that
// decimals can be read as exact rationals (0.8 is 4/5, never 0.8000000000000000444).
#pragma once

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace impactgen
{

/// Bad input: the message names the problem and, where there is one, the key.
class input_error : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

class json_value
{
public:
    enum class kind { null, boolean, number, string, array, object };

    kind type() const { return kind_; }
    bool is_number() const { return kind_ == kind::number; }
    bool is_string() const { return kind_ == kind::string; }
    bool is_array() const { return kind_ == kind::array; }
    bool is_object() const { return kind_ == kind::object; }

    /// The literal text of a number, or the contents of a string.
    const std::string &text() const { return text_; }
    const std::vector<json_value> &items() const { return items_; }
    /// Object members in the order written.
    const std::vector<std::pair<std::string, json_value>> &members() const { return members_; }
    /// The member named key, or nullptr.
    const json_value *find(const std::string &key) const;

    static const char *kind_name(kind k);

    /// Parses text; throws input_error naming the position of malformed JSON
    /// and any key written twice in one object.
    static json_value parse(const std::string &text);

private:
    friend class json_builder;
    kind kind_ = kind::null;
    std::string text_;
    std::vector<json_value> items_;
    std::vector<std::pair<std::string, json_value>> members_;
};

} // namespace impactgen
