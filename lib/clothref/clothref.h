// Everything a program using clothref usually needs, in one include: scenes (built-in and JSON),
// worlds and their step, state hashes, and traces written and read back. Areas with their own
// purpose (diff, golden, verify, analysis) keep their own headers.
#pragma once

#include "clothref/core/world.h"
#include "clothref/record/record.h"
#include "clothref/record/world_views.h"
#include "clothref/scene/make_world.h"
#include "clothref/scene/scene.h"
#include "clothref/trace/hash.h"
#include "clothref/trace/reader.h"
