// The title a document gives its problem: the problem's own "title" when the
// file has one, else a person's name for it -- a named class's name in words,
// or a file's base name (no folder, no ".json") after the kind of impact.
// Never a path: a hand-out printed unedited must not show where a file lay.
#pragma once

#include "symbolic/problem.hpp"

#include <string>

namespace impactgen::print
{

/// The document's title. `kind` names the kind of impact for an untitled file
/// ("Smooth impact", "Impact with Coulomb friction"): "Smooth impact: hinged-rod".
std::string document_title(const problem &p, const std::string &kind);

/// A named class's name in words ("pinned-planar": "A ball strikes a hinged rod"), or ""
/// when `name` is not a named class.
std::string class_name_in_words(const std::string &name);

/// The base name of a problem's source without folder and ".json" ("/a/b/hinged-rod.json":
/// "hinged-rod").
std::string source_stem(const std::string &source);

} // namespace impactgen::print
