#pragma once
// The jellyfish scene's [[objects]] entries as parameter tables: for each object type (jellyfish,
// circle, box, polygon, ib2d) and an ib2d object's [[objects.schedules]], its fields with their
// type, unit, allowed values, default and meaning. The tables alone say which fields a type has
// (an unknown one is refused, naming the allowed), check each field's value and give
// docs/parameters.md's [[objects]] section; the readers build the physics specs from them.
#include <string>
#include <vector>

#include "jellysim/config/config.hpp"
#include "jellysim/coupling/world.hpp"
#include "jellysim/jellyfish/ib2d_object.hpp"
#include "jellysim/jellyfish/obstacle.hpp"
#include "jellysim/scene/parameters.hpp"

namespace jellysim::scene {

/// "jellyfish", "circle", "box", "polygon", "ib2d": the values of an object's `type`.
const std::vector<std::string>& object_types();
/// The fields of an object of `type` (one of object_types()), or of "schedules" (an ib2d object's
/// [[objects.schedules]]). Fields without a default are required or optional as the description
/// says. Throws std::logic_error for another name.
const ParameterTable& object_parameters(const std::string& type);

/// A rigid obstacle (`type` circle, box or polygon) from its [[objects]] table `o`; `where` names it
/// in messages ("objects[2] (circle)"). Throws InputError.
jellyfish::ObstacleSpec read_obstacle(const config::Config& o, const std::string& type, const std::string& where);
/// An IB2d structure (`type` ib2d) in the tank `tank`. Throws InputError.
jellyfish::Ib2dObjectSpec read_ib2d_object(const config::Config& o, const std::string& where,
                                           const coupling::TankSpec& tank);

/// The reference page's [[objects]] section: a table per object type.
std::string objects_reference_markdown();

}  // namespace jellysim::scene
