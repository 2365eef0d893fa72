// Documentation of every Lua API function: the one source for help() in the console and for
// docs/lua-api.md (`seismpm --api-doc` writes it; a test checks the two agree).
#pragma once

#include <string>
#include <vector>

namespace seismpm::lua {

struct ApiDoc {
  const char* name;       // "mpm.model", "model:run"
  const char* signature;  // "mpm.model{ domain, cell, shape, ... }"
  const char* summary;    // what it does, keys with units and ranges
  const char* example;    // a line of Lua
};

const std::vector<ApiDoc>& api_docs();
const ApiDoc* find_doc(const std::string& name);
// The whole reference as Markdown.
std::string api_markdown();

}  // namespace seismpm::lua
