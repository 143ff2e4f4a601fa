// The generated parts of docs/passes/<Type>.md: the field and parameter tables, made from the
// pass registry (reflect + the ParamVisitor declarations), so the docs cannot drift from the code.
// Each page holds them between marker comments; `fovea passes --update-docs DIR` rewrites them and
// `fovea passes --check-docs DIR` (a test) fails when a page is stale or missing.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fovea::app {

// The two tables of one pass type as markdown, from describePass()'s JSON.
std::string fieldsMarkdown(const nlohmann::json& pass);
std::string paramsMarkdown(const nlohmann::json& pass);

// Replaces the generated blocks of `page` (the text of <Type>.md) with the tables of `pass`.
// Throws InputError naming `file` when a marker pair is missing.
std::string updatePassPage(const std::string& page, const nlohmann::json& pass,
                           const std::string& file);

// Checks or rewrites DIR/<Type>.md for every pass in `passes`; returns one line per stale or
// missing page (empty = all current). With `write`, stale pages are rewritten and missing ones
// created as a starter page (title, summary, the tables); pages without markers are reported.
std::vector<std::string> syncPassDocs(const std::string& dir, const nlohmann::json& passes,
                                      bool write);

}  // namespace fovea::app
