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
// The whole reference as Markdown.
std::string api_markdown();

}  // namespace seismpm::lua
