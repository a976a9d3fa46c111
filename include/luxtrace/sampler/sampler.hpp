#pragma once
// Only for files still including philox_sampler.hpp by its former name (src/tracer/probe.cpp):
// delete this header once none does.
#include "luxtrace/sampler/philox_sampler.hpp"
