#pragma once
/// @file The list of the library's impact laws. A law is a value type in its own folder, with its
/// parameters, checks, file schema, residual, certificate terms and solver chain
/// (docs/architecture.md); adding one is its folder and one line here.
#include <variant>

#include "fremond/laws/fremond/fremond_law.hpp"
#include "fremond/laws/restitution/restitution_law.hpp"
#include "fremond/laws/stronge/stronge_law.hpp"

namespace fremond {

using LawVariant = std::variant<RestitutionLaw, FremondLaw, StrongeLaw>;

}  // namespace fremond
