#pragma once
// Internal to the bake: its stages (docs/algorithms.md §4), one owner each, in the order bake.cpp runs
// them, each a function so that tests can check it on hand-made input (closed forms, hard cases)
// without running a whole bake:
//   coverage.h  1    the pixel coverage of every Gaussian in every bake camera
//   cells.h     2–3  normalised positions; the cells the Gaussians small at a level pool by
//   pooling.h   4–5  one pooled Gaussian per cell, enlarged towards S_T
//   ranges.h    6    the coverage range in which each Gaussian is drawn
//   refine.h    7    the refinement of each coarse level against the fine model
//   order.h          the order of the baked Gaussians in the file
// (the cameras are bake_cameras.h's, the progress and stage times stage_clock.h's).
#include "cells.h"
#include "coverage.h"
#include "order.h"
#include "pooling.h"
#include "ranges.h"
#include "refine.h"
#include "stage_clock.h"
