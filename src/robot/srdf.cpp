#include <tinyxml2.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/robot/srdf.hpp>
#include <iomanip>
#include <limits>
#include <sstream>

namespace hullcheck {
namespace {

using tinyxml2::XMLElement;

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  std::string required(const XMLElement& e, const char* attribute) const {
    const char* value = e.Attribute(attribute);
    if (value == nullptr || *value == '\0') {
      std::ostringstream msg;
      msg << "SRDF '" << source_ << "': line " << e.GetLineNum() << ": <" << e.Name()
          << "> needs attribute '" << attribute << "'";
      throw InputError(msg.str());
    }
    return value;
  }

  static std::string optional(const XMLElement& e, const char* attribute) {
    const char* value = e.Attribute(attribute);
    return value == nullptr ? std::string() : std::string(value);
  }

  double number(const XMLElement& e, const char* attribute) const {
    const std::string text = required(e, attribute);
    // Multi-DOF joints list several values; hullcheck's joints have one (the first). Every
    // value must be a whole finite number: "0.5rad" or "1,5" is an error, not 0.5 or 1.
    std::istringstream in(text);
    in.imbue(std::locale::classic());
    double value = 0.0;
    bool ok = false;
    std::string token;
    for (int i = 0; in >> token; ++i) {
      std::istringstream t(token);
      t.imbue(std::locale::classic());
      double v = 0.0;
      ok = (t >> v) && t.peek() == std::char_traits<char>::eof() && std::isfinite(v);
      if (!ok) break;
      if (i == 0) value = v;
    }
    if (!ok) {
      std::ostringstream msg;
      msg << "SRDF '" << source_ << "': line " << e.GetLineNum() << ": <" << e.Name() << " "
          << attribute << "='" << text << "'> is not a finite number";
      throw InputError(msg.str());
    }
    return value;
  }

  SrdfGroup group(const XMLElement& g) const {
    SrdfGroup out;
    out.name = required(g, "name");
    for (const XMLElement* c = g.FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
      const std::string tag = c->Name();
      if (tag == "joint") {
        out.joints.push_back(required(*c, "name"));
      } else if (tag == "link") {
        out.links.push_back(required(*c, "name"));
      } else if (tag == "chain") {
        out.chains.emplace_back(required(*c, "base_link"), required(*c, "tip_link"));
      } else if (tag == "group") {
        out.subgroups.push_back(required(*c, "name"));
      }
    }
    return out;
  }

  SrdfLinkPair pair(const XMLElement& e) const {
    return {required(e, "link1"), required(e, "link2"), optional(e, "reason")};
  }

 private:
  std::string source_;
};

// The shortest decimal text (up to 17 significant digits) that reads back as `value`.
std::string shortest_text(double value) {
  std::string text;
  for (int digits = 1; digits <= std::numeric_limits<double>::max_digits10; ++digits) {
    std::ostringstream out;
    out.imbue(std::locale::classic());
    out << std::setprecision(digits) << value;
    text = out.str();
    std::istringstream in(text);
    in.imbue(std::locale::classic());
    double back = 0.0;
    if (in >> back && back == value) break;
  }
  return text;
}

}  // namespace

const SrdfGroup* Srdf::group(const std::string& name) const {
  for (const SrdfGroup& g : groups) {
    if (g.name == name) return &g;
  }
  return nullptr;
}

const SrdfGroupState* Srdf::group_state(const std::string& group_name,
                                        const std::string& name) const {
  for (const SrdfGroupState& s : group_states) {
    if (s.group == group_name && s.name == name) return &s;
  }
  return nullptr;
}

Srdf read_srdf_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("SRDF '" + path + "': cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_srdf(text.str(), path);
}

Srdf parse_srdf(const std::string& xml, const std::string& source_name) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    throw InputError("SRDF '" + source_name + "': malformed XML: " + doc.ErrorStr());
  }
  const XMLElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) throw InputError("SRDF '" + source_name + "': no <robot> root element");
  const Reader r(source_name);
  Srdf srdf;
  srdf.robot_name = Reader::optional(*robot, "name");
  for (const XMLElement* e = robot->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "virtual_joint") {
      srdf.virtual_joints.push_back({r.required(*e, "name"), r.required(*e, "type"),
                                     r.required(*e, "parent_frame"), r.required(*e, "child_link")});
    } else if (tag == "group") {
      srdf.groups.push_back(r.group(*e));
    } else if (tag == "group_state") {
      SrdfGroupState state;
      state.name = r.required(*e, "name");
      state.group = r.required(*e, "group");
      for (const XMLElement* j = e->FirstChildElement("joint"); j != nullptr;
           j = j->NextSiblingElement("joint")) {
        state.joint_values.emplace_back(r.required(*j, "name"), r.number(*j, "value"));
      }
      srdf.group_states.push_back(std::move(state));
    } else if (tag == "end_effector") {
      srdf.end_effectors.push_back({r.required(*e, "name"), r.required(*e, "group"),
                                    r.required(*e, "parent_link"),
                                    Reader::optional(*e, "parent_group")});
    } else if (tag == "disable_collisions") {
      srdf.disabled_collisions.push_back(r.pair(*e));
    } else if (tag == "enable_collisions") {
      srdf.enabled_collisions.push_back(r.pair(*e));
    } else if (tag == "disable_default_collisions") {
      srdf.disabled_links.push_back(r.required(*e, "link"));
    }
  }
  return srdf;
}

std::string write_srdf(const Srdf& srdf, const std::string& comment) {
  tinyxml2::XMLDocument doc;
  doc.InsertEndChild(doc.NewDeclaration());
  if (!comment.empty()) doc.InsertEndChild(doc.NewComment((" " + comment + " ").c_str()));
  XMLElement* robot = doc.NewElement("robot");
  robot->SetAttribute("name", srdf.robot_name.c_str());
  doc.InsertEndChild(robot);
  for (const SrdfVirtualJoint& v : srdf.virtual_joints) {
    XMLElement* e = robot->InsertNewChildElement("virtual_joint");
    e->SetAttribute("name", v.name.c_str());
    e->SetAttribute("type", v.type.c_str());
    e->SetAttribute("parent_frame", v.parent_frame.c_str());
    e->SetAttribute("child_link", v.child_link.c_str());
  }
  for (const SrdfGroup& g : srdf.groups) {
    XMLElement* e = robot->InsertNewChildElement("group");
    e->SetAttribute("name", g.name.c_str());
    for (const std::string& j : g.joints) {
      e->InsertNewChildElement("joint")->SetAttribute("name", j.c_str());
    }
    for (const std::string& l : g.links) {
      e->InsertNewChildElement("link")->SetAttribute("name", l.c_str());
    }
    for (const auto& [base, tip] : g.chains) {
      XMLElement* c = e->InsertNewChildElement("chain");
      c->SetAttribute("base_link", base.c_str());
      c->SetAttribute("tip_link", tip.c_str());
    }
    for (const std::string& s : g.subgroups) {
      e->InsertNewChildElement("group")->SetAttribute("name", s.c_str());
    }
  }
  for (const SrdfGroupState& s : srdf.group_states) {
    XMLElement* e = robot->InsertNewChildElement("group_state");
    e->SetAttribute("name", s.name.c_str());
    e->SetAttribute("group", s.group.c_str());
    for (const auto& [joint, value] : s.joint_values) {
      XMLElement* j = e->InsertNewChildElement("joint");
      j->SetAttribute("name", joint.c_str());
      j->SetAttribute("value", shortest_text(value).c_str());
    }
  }
  for (const SrdfEndEffector& ee : srdf.end_effectors) {
    XMLElement* e = robot->InsertNewChildElement("end_effector");
    e->SetAttribute("name", ee.name.c_str());
    e->SetAttribute("parent_link", ee.parent_link.c_str());
    e->SetAttribute("group", ee.group.c_str());
    if (!ee.parent_group.empty()) e->SetAttribute("parent_group", ee.parent_group.c_str());
  }
  for (const std::string& l : srdf.disabled_links) {
    robot->InsertNewChildElement("disable_default_collisions")->SetAttribute("link", l.c_str());
  }
  const auto write_pairs = [&](const char* tag, const std::vector<SrdfLinkPair>& pairs) {
    for (const SrdfLinkPair& p : pairs) {
      XMLElement* e = robot->InsertNewChildElement(tag);
      e->SetAttribute("link1", p.link1.c_str());
      e->SetAttribute("link2", p.link2.c_str());
      if (!p.reason.empty()) e->SetAttribute("reason", p.reason.c_str());
    }
  };
  write_pairs("disable_collisions", srdf.disabled_collisions);
  write_pairs("enable_collisions", srdf.enabled_collisions);
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

}  // namespace hullcheck
