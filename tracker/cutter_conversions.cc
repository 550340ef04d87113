#include "tracker/cutter_conversions.h"

#include <cmath>

namespace minenav {

cutter_command_t ToLcm(const CutterCommand& c) {
  cutter_command_t m{};
  m.utime = c.utime;
  m.seq = c.seq;
  m.action = static_cast<int8_t>(c.action);
  m.boom_height = c.boom_height;
  m.sump_depth = c.sump_depth;
  if (c.face) {
    m.face_x1 = c.face->a.x();
    m.face_y1 = c.face->a.y();
    m.face_x2 = c.face->b.x();
    m.face_y2 = c.face->b.y();
  }
  return m;
}

std::optional<CutterCommand> CutterCommandFromLcm(const cutter_command_t& m, std::string* why) {
  if (m.action < cutter_command_t::IDLE || m.action > cutter_command_t::STOP) {
    *why = "cutter command: unknown action " + std::to_string(m.action);
    return std::nullopt;
  }
  for (double v : {m.boom_height, m.sump_depth, m.face_x1, m.face_y1, m.face_x2, m.face_y2})
    if (!std::isfinite(v)) {
      *why = "cutter command: a number is not finite";
      return std::nullopt;
    }
  CutterCommand c;
  c.utime = m.utime;
  c.seq = m.seq;
  c.action = static_cast<CutterCommand::Action>(m.action);
  c.boom_height = m.boom_height;
  c.sump_depth = m.sump_depth;
  const Segment face(m.face_x1, m.face_y1, m.face_x2, m.face_y2);
  if (face.length() > 0.0) c.face = face;
  return c;
}

cutter_state_t ToLcm(const CutterState& s) {
  cutter_state_t m{};
  m.utime = s.utime;
  m.phase = static_cast<int8_t>(s.phase);
  m.drum_on = s.drum_on;
  m.boom_height = s.boom_height;
  m.sumped_depth = s.sumped_depth;
  m.coal_removed = s.coal_removed;
  m.message = s.message;
  return m;
}

std::optional<CutterState> CutterStateFromLcm(const cutter_state_t& m, std::string* why) {
  if (m.phase < cutter_state_t::IDLE || m.phase > cutter_state_t::FAULT) {
    *why = "cutter state: unknown phase " + std::to_string(m.phase);
    return std::nullopt;
  }
  for (double v : {m.boom_height, m.sumped_depth, m.coal_removed})
    if (!std::isfinite(v)) {
      *why = "cutter state: a number is not finite";
      return std::nullopt;
    }
  CutterState s;
  s.utime = m.utime;
  s.phase = static_cast<CutterState::Phase>(m.phase);
  s.drum_on = m.drum_on;
  s.boom_height = m.boom_height;
  s.sumped_depth = m.sumped_depth;
  s.coal_removed = m.coal_removed;
  s.message = m.message.substr(0, 300);
  return s;
}

}  // namespace minenav
