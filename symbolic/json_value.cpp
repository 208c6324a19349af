#include "json_value.hpp"

#include <nlohmann/json.hpp>

namespace impactgen
{

const json_value *json_value::find(const std::string &key) const
{
    for (const auto &m : members_)
        if (m.first == key)
            return &m.second;
    return nullptr;
}

const char *json_value::kind_name(kind k)
{
    switch (k) {
    case kind::null:
        return "null";
    case kind::boolean:
        return "a boolean";
    case kind::number:
        return "a number";
    case kind::string:
        return "a string";
    case kind::array:
        return "a list";
    case kind::object:
        return "an object";
    }
    return "?";
}

// SAX handler building json_value; nlohmann hands us the literal text of
// floating-point numbers, and integers are exact anyway.
class json_builder : public nlohmann::json_sax<nlohmann::json>
{
public:
    json_value root;

    bool null() override { return put(make(json_value::kind::null, "")); }
    bool boolean(bool v) override { return put(make(json_value::kind::boolean, v ? "true" : "false")); }
    bool number_integer(number_integer_t v) override { return put(make(json_value::kind::number, std::to_string(v))); }
    bool number_unsigned(number_unsigned_t v) override
    {
        return put(make(json_value::kind::number, std::to_string(v)));
    }
    bool number_float(number_float_t, const string_t &s) override { return put(make(json_value::kind::number, s)); }
    bool string(string_t &s) override { return put(make(json_value::kind::string, s)); }
    bool binary(binary_t &) override { throw input_error("malformed JSON: binary values are not JSON text"); }
    bool start_object(std::size_t) override
    {
        check_depth();
        stack_.push_back({make(json_value::kind::object, ""), pending_key_});
        return true;
    }
    bool key(string_t &k) override
    {
        const json_value &obj = stack_.back().value;
        if (obj.find(k))
            throw input_error("malformed JSON: key \"" + k + "\" is written twice in one object");
        pending_key_ = k;
        return true;
    }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override
    {
        check_depth();
        stack_.push_back({make(json_value::kind::array, ""), pending_key_});
        return true;
    }
    bool end_array() override { return close(); }
    bool parse_error(std::size_t pos, const std::string &, const nlohmann::detail::exception &ex) override
    {
        std::string what = ex.what();
        if (what.find("number overflow") != std::string::npos)
            throw input_error((pending_key_.empty() ? std::string("value") : pending_key_) +
                              ": a number out of the range of double (above about 1e308) at byte " +
                              std::to_string(pos));
        // nlohmann's text is "[json.exception.parse_error.101] parse error at line 1, column 3: ..."
        auto colon = what.find("] ");
        throw input_error("malformed JSON (byte " + std::to_string(pos) +
                          "): " + (colon == std::string::npos ? what : what.substr(colon + 2)));
    }

private:
    // The problem format nests four levels deep; a bound keeps absurd input
    // from exhausting the stack (the tree is built and freed recursively).
    static constexpr std::size_t max_depth = 64;
    void check_depth() const
    {
        if (stack_.size() >= max_depth)
            throw input_error("malformed JSON: nested deeper than " + std::to_string(max_depth) + " levels");
    }

    struct frame {
        json_value value;
        std::string key; // the key under which the container is stored in its parent
    };
    std::vector<frame> stack_;
    std::string pending_key_;
    bool have_root_ = false;

    static json_value make(json_value::kind k, std::string text)
    {
        json_value v;
        v.kind_ = k;
        v.text_ = std::move(text);
        return v;
    }
    bool put(json_value v) { return attach(std::move(v), pending_key_); }
    bool attach(json_value v, const std::string &key)
    {
        if (stack_.empty()) {
            root = std::move(v);
            have_root_ = true;
            return true;
        }
        json_value &top = stack_.back().value;
        if (top.kind_ == json_value::kind::object)
            top.members_.emplace_back(key, std::move(v));
        else
            top.items_.push_back(std::move(v));
        return true;
    }
    bool close()
    {
        frame f = std::move(stack_.back());
        stack_.pop_back();
        return attach(std::move(f.value), f.key);
    }
};

json_value json_value::parse(const std::string &text)
{
    json_builder b;
    nlohmann::json::sax_parse(text, &b);
    return b.root;
}

} // namespace impactgen
