// Sections: named step lists a file keeps under `sections`, performed by a `section` step,
// optionally with `params` (names and default values) given values by `with` and put in for
// every `$name` / `${name}` in the section's steps, or worked out where a value is an expression
// of them (param_expressions.hpp). The step walk (step_walk.hpp) calls these;
// each reports what is wrong with what it reads and returns nullptr or nothing.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/scope_chain.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"

namespace seqc::compiler {

// A file's `sections` (a map of names to step lists, or to {params, steps}) into `scope`.
void read_sections(const YamlNode& sections, FileScope& scope, Reporter& reporter);

// The steps of a performance of `section` (called `name`, performed by `step`) with its
// parameters' values put in for every `$name` and every expression of them worked out; nullptr
// after reporting (an unknown name, a mistake in an expression). `copy` holds them when
// anything was put in; `performance` gets the note naming the values, when there are any.
const YamlNode* perform_section(const YamlNode& step, const YamlNode& name, const YamlNode& section,
                                YamlNode& copy, std::optional<Reporter::Note>& performance,
                                Reporter& reporter);

// Performs the section a `section` step (`step`, naming it in `value`) names, from the running
// files' sections: reports an unknown name, a section that performs itself (`running`, the
// sections running now, outermost first) and any mistake in its parameters; otherwise calls
// `run` with its steps and a name for them, with the performance named in every message from
// inside it.
void run_section(const YamlNode& step, const YamlNode& value, const ScopeChain& scopes,
                 std::vector<const YamlNode*>& running, Reporter& reporter,
                 const std::function<void(const YamlNode& steps, const std::string& what)>& run);

}  // namespace seqc::compiler
