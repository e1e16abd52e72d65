// <actor> (SDF 1.6, sdformat's sdf/1.6/actor.sdf) -> ActorDescription, as Gazebo 11's
// Actor::Load / LoadScript reads it (gazebo/physics/Actor.cc); docs/actors.md.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <string>

#include "tianracer_sim/common/input_limits.h"
#include "tianracer_sim/common/text.h"
#include "world_parser.h"

namespace tianracer_sim {
namespace world_internal {

ActorDescription Parser::parseActor(const XMLElement* e) {
  ActorDescription a;
  a.line = e->GetLineNum();
  a.model.line = a.line;
  a.model.name = attributeText(e, "name");
  if (a.model.name.empty()) fail(e, "<actor> has no name");
  const std::string what = "actor '" + a.model.name + "'";
  std::set<std::string> link_names;
  const XMLElement* script = nullptr;
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "pose") {
      a.model.X_WM = pose(c, what, a.model.X_WM);
    } else if (tag == "link") {
      LinkDescription l = parseLink(c, a.model.name);
      if (!link_names.insert(l.name).second)
        fail(c, what + ": duplicate link name '" + l.name + "'");
      a.model.links.push_back(std::move(l));
    } else if (tag == "script") {
      if (script) fail(c, what + ": a second <script>");
      script = c;
    } else if (tag == "static") {
      // Gazebo's actors are static by default (sdf/1.6/actor.sdf); a dynamic one is not.
      if (!boolean(c, what))
        warn(c, what + ": <static>false</static> is not simulated (Gazebo's dynamic actor links "
                       "fall between frames): the actor is moved kinematically");
    } else if (tag == "skin" || tag == "animation") {
      // Skeletal meshes (COLLADA/BVH) are not loaded: the actor is its <link>s.
      warn(c, "<" + tag + "> in <actor> is not simulated (no skeletal animation): " + what +
                  " is seen and touched through its <link>s only");
    } else {
      unsupported(c);
    }
  }
  if (a.model.links.empty())
    warn(e, what + " has no <link>: its script moves nothing that sensors see");
  if (!script) return a;  // Gazebo: no script, the actor stands at its <pose>

  ActorScript& s = a.script;
  std::vector<const XMLElement*> trajectories;
  for (const XMLElement* c = script->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "loop") {
      s.loop = boolean(c, what + " <script>");
    } else if (tag == "delay_start") {
      // Gazebo takes any value, a negative one too; bounded as waypoint times are.
      s.delay_start = bounded(c, what + " <script>", limits::kPosition, "s");
    } else if (tag == "auto_start") {
      s.auto_start = boolean(c, what + " <script>");
    } else if (tag == "trajectory") {
      trajectories.push_back(c);
    } else {
      unsupported(c);
    }
  }
  for (const XMLElement* c : trajectories) {
    ActorTrajectory tr;
    tr.line = c->GetLineNum();
    const char* id = c->Attribute("id");
    const std::string id_text = id ? trimText(id) : "";
    const std::string twhat = what + " <trajectory id='" + id_text + "'>";
    tr.id = integerAttribute(c, "id", what);
    tr.type = attributeText(c, "type");
    if (c->Attribute("tension")) tr.tension = numberAttribute(c, "tension", what);
    std::map<double, int> times;  // time -> line
    for (const XMLElement* w = c->FirstChildElement(); w; w = w->NextSiblingElement()) {
      if (std::string(w->Name()) != "waypoint") {
        unsupported(w);
        continue;
      }
      ActorWaypoint wp;
      wp.line = w->GetLineNum();
      const XMLElement* te = required(w, "time", twhat + " <waypoint>");
      const XMLElement* pe = required(w, "pose", twhat + " <waypoint>");
      wp.time = number(te, twhat + " <waypoint>");
      if (wp.time < 0.0)
        fail(te, twhat + ": <waypoint> <time> " + text(te) + " is negative");
      if (wp.time > limits::kPosition)  // a day-long waypoint is still fine; 1e6 s bounds it
        fail(te, twhat + ": <waypoint> <time> " + text(te) + " is out of range (<= " +
                     limits::formatNumber(limits::kPosition) + " s)");
      const auto dup = times.find(wp.time);
      if (dup != times.end())
        fail(te, twhat + ": <waypoint> <time> " + text(te) +
                     " is the time of the waypoint at line " + std::to_string(dup->second) +
                     " too (Gazebo keeps only the last)");
      times[wp.time] = wp.line;
      const Eigen::Isometry3d X = pose(pe, twhat + " <waypoint>");  // checks it
      const std::vector<double> n = numbers(pe, twhat + " <waypoint>");
      wp.position = X.translation();
      wp.rotation = actorRotation(n[3], n[4], n[5]);
      for (const XMLElement* k = w->FirstChildElement(); k; k = k->NextSiblingElement()) {
        const std::string kt = k->Name();
        if (kt != "time" && kt != "pose") unsupported(k);
      }
      tr.waypoints.push_back(wp);
    }
    if (tr.waypoints.empty())
      fail(c, twhat + " has no <waypoint> (nothing to play; skeletal animations are not "
                      "simulated)");
    std::stable_sort(tr.waypoints.begin(), tr.waypoints.end(),
                     [](const ActorWaypoint& x, const ActorWaypoint& y) { return x.time < y.time; });
    // Played in ascending id; equal ids after the earlier ones (Actor::LoadScript's insert).
    auto at = std::upper_bound(
        s.trajectories.begin(), s.trajectories.end(), tr.id,
        [](int id, const ActorTrajectory& t) { return id < t.id; });
    s.trajectories.insert(at, std::move(tr));
  }
  return a;
}

}  // namespace world_internal
}  // namespace tianracer_sim
