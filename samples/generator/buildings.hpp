// samples/generator/buildings.hpp — the sample buildings, each appended to an ObjBuilder as one or
// more objects with their materials (docs/CONVERTER.md lists what each one exercises).
#pragma once

#include "obj_builder.hpp"

namespace nut::samples {

// 40 storeys over a 5 m base, a regular grid of recessed windows with mullions, transoms, sills
// and trims on all four facades, shop windows, a parapet and a machine room: the largest sample.
void highRise(ObjBuilder& out);
// Five storeys, recessed windows, balconies with railings, chimneys and a pitched (gable) roof.
void residential(ObjBuilder& out);
// Four decks on square pillars, parapets with a painted band, straight ramps between the decks
// (sloped along x) and a stair tower.
void carPark(ObjBuilder& out);
// Two storeys with round corners (quarter cylinders) and a domed rotunda on the flat roof.
void house(ObjBuilder& out);
// A 2 x 2 street block of touching buildings of different heights, one OBJ object each.
void streetBlock(ObjBuilder& out);

}  // namespace nut::samples
