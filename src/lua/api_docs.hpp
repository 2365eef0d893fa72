// The API reference, assembled from the key tables of the binding files (arg_spec.hpp): help() in the
// console and docs/lua-api.md (`seismpm --api-doc` writes it; a test checks the two agree).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "arg_spec.hpp"

namespace seismpm::lua {

// The table of each binding file.
std::span<const Function> model_functions();
std::span<const Function> model_building_functions();
std::span<const Function> phase_functions();
std::span<const Function> output_functions();
std::span<const Function> body_functions();
std::span<const Function> probe_functions();
std::span<const Function> material_functions();
std::span<const Function> shape_functions();
std::span<const Function> history_functions();
std::span<const Function> methods_functions();  // mpm.newmark
std::span<const Function> plot_functions();
std::span<const Function> session_functions();  // mpm.param, mpm.version, mpm.out_dir
std::span<const Function> help_functions();
std::span<const Function> lem_functions();
std::span<const Function> strength_reduction_functions();
std::span<const Function> checkpoint_functions();  // m:checkpoint, mpm.restart
std::span<const Function> library_functions();     // lua/seismpm.lua

struct ApiSection {
  const char* title;
  std::span<const Function> functions;
};

// The reference in its order: sections of the binding files' tables.
const std::vector<ApiSection>& api_sections();
// Every function, in that order.
const std::vector<const Function*>& api_functions();
const Function* find_function(const std::string& name);

// "mpm.model{ domain, cell, shape = "gimp", ... }"
std::string signature(const Function& f);
// What help("name") shows: signature, summary, one line per key, example.
std::string help_text(const Function& f);
// The first sentence of its summary, shortened to about 100 characters: what a listing shows.
std::string summary_line(const Function& f);
// One line per function, "  name  summary line", the names aligned.
std::string listing(const std::vector<const Function*>& functions);
// The functions whose name, summary or keys (names and texts) hold `query`, ignoring case.
std::vector<const Function*> search(const std::string& query);
// What help("query") shows when no function has that name: the listing of the matches, or a line
// saying that nothing matched.
std::string search_text(const std::string& query);
// What help(value) prints for the value at `index` (help_binding.cpp): the overview, one function, a table
// of the API, an object's methods, or a search. It never raises: for a value that is not part of the API it
// says so, and a string that names nothing is searched for.
std::string help_for(lua_State* L, int index);
// The whole reference as Markdown.
std::string api_markdown();

}  // namespace seismpm::lua
