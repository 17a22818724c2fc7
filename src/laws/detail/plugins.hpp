#pragma once
// The hooks of every law of fremond/laws/law_list.hpp, for the generic driver: one line a law.
#include "laws/fremond/plugin.hpp"
#include "laws/restitution/plugin.hpp"
#include "laws/stronge/plugin.hpp"
