// Defect 1 of issue 25: a document's title is the problem's "title" when the file has one,
// else a person's name for it (a named class's name in words, a file's base name), never a
// path; the "description" stands under the title in every format.
#include "print/explain.hpp"
#include "print/title.hpp"
#include "symbolic/named_classes.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace impactgen;

namespace
{

print::document document_of(const problem &p)
{
    const derivation d = derive(p);
    return print::explain(d, solve_impact(d));
}

std::string hinged_rod_path() { return std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/hinged-rod.json"; }

} // namespace

TEST(DocumentTitle, FileWithoutTitleIsNamedByItsBaseNameNeverItsPath)
{
    const print::document doc = document_of(load_problem_file(hinged_rod_path()));
    EXPECT_EQ(doc.title, "Smooth impact: hinged-rod");
    for (const std::string &out : {print::explain_text(doc), print::explain_latex(doc), print::explain_html(doc)}) {
        EXPECT_EQ(out.find(IMPACTGEN_SOURCE_DIR), std::string::npos);
        EXPECT_EQ(out.find("hinged-rod.json"), std::string::npos);
    }
}

TEST(DocumentTitle, FrictionFileWithoutTitleIsNamedByItsBaseName)
{
    const std::string path = std::string(IMPACTGEN_SOURCE_DIR) + "/tests/explain/ball-floor.json";
    const print::document doc = document_of(load_problem_file(path));
    EXPECT_EQ(doc.title, "Impact with Coulomb friction: ball-floor");
}

TEST(DocumentTitle, NamedClassIsNamedInWords)
{
    for (const char *name : {"pinned-planar", "central-direct", "ball-floor-friction"}) {
        const print::document doc = document_of(find_named_class(name)->build());
        EXPECT_EQ(doc.title, print::class_name_in_words(name)) << name;
        EXPECT_EQ(doc.title.find(name), std::string::npos) << name;
        EXPECT_FALSE(doc.title.empty()) << name;
    }
    // every named class has its words
    for (const named_class &c : named_classes())
        EXPECT_FALSE(print::class_name_in_words(c.name).empty()) << c.name;
    for (const named_class &c : friction_classes())
        EXPECT_FALSE(print::class_name_in_words(c.name).empty()) << c.name;
    for (const named_class &c : law_classes())
        EXPECT_FALSE(print::class_name_in_words(c.name).empty()) << c.name;
}

TEST(DocumentTitle, TitleAndDescriptionOfTheFileStandAtTheTop)
{
    const std::string text = R"({"title": "A ball strikes a hanging rod",
      "description": "A ball of 0.5 kg strikes the lower end of a rod hanging from a hinge.",
      "dimension": 2, "restitution": 0.8,
      "bodies": [ { "name": "ball", "mass": 0.5, "position": [0, -1], "velocity": [5, 0] },
                  { "name": "rod", "mass": 2, "inertia": "1/6", "position": [0, -0.5], "velocity": [0, 0] } ],
      "contact": { "bodies": ["ball", "rod"], "point": [0, -1], "normal": [1, 0] },
      "pivots": [ { "body": "rod", "point": [0, 0] } ] })";
    const print::document doc = document_of(read_problem(text, "/somewhere/deep/rod.json"));
    EXPECT_EQ(doc.title, "A ball strikes a hanging rod");
    const std::string description = "A ball of 0.5 kg strikes the lower end of a rod hanging from a hinge.";
    EXPECT_EQ(doc.description, description);

    const std::string txt = print::explain_text(doc);
    EXPECT_EQ(txt.rfind("A ball strikes a hanging rod\n", 0), 0u);
    const std::size_t under = txt.find('\n', txt.find('\n') + 1); // after the title and its rule
    EXPECT_EQ(txt.find(description), under + 2);
    EXPECT_NE(print::explain_markdown(doc).find("# A ball strikes a hanging rod\n\n" + description), std::string::npos);
    const std::string tex = print::explain_latex(doc);
    EXPECT_NE(tex.find("\\title{A ball strikes a hanging rod}"), std::string::npos);
    const std::size_t made = tex.find("\\maketitle"), said = tex.find(description);
    ASSERT_NE(said, std::string::npos);
    EXPECT_LT(made, said);
    EXPECT_LT(said, tex.find("\\section*"));
    const std::string html = print::explain_html(doc);
    EXPECT_NE(html.find("<h1>A ball strikes a hanging rod</h1>\n<p class=\"description\">" + description + "</p>"),
              std::string::npos);
    for (const std::string &out : {txt, tex, html})
        EXPECT_EQ(out.find("/somewhere"), std::string::npos);
}

TEST(DocumentTitle, SourceStemDropsFolderAndExtension)
{
    EXPECT_EQ(print::source_stem("/a/b/hinged-rod.json"), "hinged-rod");
    EXPECT_EQ(print::source_stem("hinged-rod.json"), "hinged-rod");
    EXPECT_EQ(print::source_stem("c:\\x\\y.json"), "y");
    EXPECT_EQ(print::source_stem("planar"), "planar");
}
