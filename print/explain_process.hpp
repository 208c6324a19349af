// The document's parts for the restitution laws followed through the impact (Routh's process,
// symbolic/routh.hpp): the chapter of a contact with friction whose law is poisson or
// energetic (explain_process.cpp), the figure of its velocity path
// (explain_process_figure.cpp), and, for Newton's law with friction, why it can gain energy
// and the three laws side by side (explain_laws_compared.cpp). Private to the print library.
#pragma once

#include "explain_law.hpp"

#include "symbolic/routh.hpp"

#include <memory>
#include <string>
#include <vector>

namespace impactgen::print::detail
{

/// Routh's process as the document teaches it, for a contact whose response K and velocities
/// before impact in (e_t, n) are known: a single contact's (the chapter below) or a system's one
/// contact with its joints and pivots eliminated (explain_system.cpp).
struct process_teaching {
    process_inputs q;                   ///< K, u, mu, e and the law: numbers or the solution's steps
    std::vector<process_sequence> seqs; ///< the phase sequences that do not wedge, in order
    bool numeric = false;
    int first_row = 1; ///< the number of the process's first formula row
};

/// Routh's process and the law's end of restitution (rows (1) to (3)).
std::vector<section> process_statement(const process_teaching &t);
/// The relative velocity as a function of the impulse, K and u, the phases' slopes (rows (4) to (7)).
std::vector<section> process_equations(const process_teaching &t);
/// A section per phase sequence: its conditions, its phases, the end of compression and of the impact.
std::vector<section> process_sequences(const process_teaching &t);
/// The path of (u_t, u_n) of the first sequence, listed and drawn (a numeric problem's one).
section process_path_section(const process_teaching &t);

/// The chapter of a contact with friction and law poisson or energetic.
std::unique_ptr<law_chapter> process_chapter(const explain_input &in);

/// What a restitution law followed through the impact says in the documents: the one hook a law
/// adds to them (explain_process.cpp, words_of; the chapter and the summary read nothing else
/// of the law). A new alternative of restitution_law does not build until it has its words.
struct restitution_words {
    std::string title;             ///< the chapter's title
    paragraph setup;               ///< the set-up's sentence on how restitution is measured
    math_row end;                  ///< the end of restitution, in the process section
    math_row summary_end;          ///< the end of restitution, in a summary
    bool compression_work = false; ///< the solution lists the normal work of compression W_c
};
restitution_words words_of(const restitution_law &law);

/// One point of the relative velocity's path: the normal impulse and (u_t, u_n) there.
struct path_point {
    double pn = 0, ut = 0, un = 0;
    std::string label; ///< "start", "slip stops", "compression ends", "end", ...
};

/// The path of (u_t, u_n), piecewise linear in P_n, drawn in TikZ and SVG with its points marked.
figure_art process_figure(const std::vector<path_point> &path, const std::string &caption);

/// After the results of a numeric planar problem with friction under Newton's law (the end of
/// Coulomb's chapter, explain_law_coulomb.cpp): why it gains energy (when it does) and the three
/// laws side by side, each solved by the library. Empty otherwise.
std::vector<section> laws_compared(const explain_input &in);

} // namespace impactgen::print::detail
