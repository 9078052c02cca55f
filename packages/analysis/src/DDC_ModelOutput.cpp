#include "DDC_ModelOutput.hpp"

#include <map>

namespace ddc {

namespace {

/// The contact slot of each mesh node that is a slave node, -1 for the
/// others (the slots are replicated; a slot names its slave node by its id
/// in the whole mesh); empty without contact.
std::vector<int> slaveSlotOfNode(const Model& model) {
  std::vector<int> slotOf(model.hasContact() ? model.mesh().numNodes() : 0, -1);
  const auto& slots = model.contactSlots();
  for (size_t k = 0; k < slots.size(); ++k) {
    const int n = model.mesh().localNode(slots[k].slaveNode);
    if (n >= 0) slotOf[size_t(n)] = int(k);
  }
  return slotOf;
}

/// The contact slots as output writes them: the values of the slave nodes
/// of this rank's elements brought from the slots' owners (an active-set
/// update leaves them current only where a slot is evaluated), and the slot
/// of each mesh node. Collective.
struct OutputSlots {
  std::vector<ContactSlot> slots;
  std::vector<int> slotOf;  ///< slaveSlotOfNode()
};

OutputSlots outputSlots(const Model& model) {
  OutputSlots o;
  o.slotOf = slaveSlotOfNode(model);
  if (!model.hasContact()) return o;
  o.slots = model.contactSlots();
  std::vector<char> written(o.slots.size(), 0);
  const Mesh& mesh = model.mesh();
  for (int e : model.localElements())
    for (int i = 0; i < mesh.elementNumNodes(e); ++i)
      if (const int k = o.slotOf[size_t(mesh.elementNodes(e)[i])]; k >= 0) written[size_t(k)] = 1;
  std::vector<int> wanted;
  for (size_t k = 0; k < written.size(); ++k)
    if (written[k]) wanted.push_back(int(k));
  model.contact()->shareSlotValues(o.slots, wanted);
  return o;
}

}  // namespace

void forEachLocalElementOutput(const Model& model, const Vector& uOverlap,
                               const std::function<void(const ElementOutput&)>& f) {
  const Mesh& mesh = model.mesh();
  const auto& ovMap = *model.overlapMap();
  auto ud = uOverlap.getData();
  const int dim = mesh.dim();
  Eigen::MatrixXd X, ue;
  for (int e : model.localElements()) {
    const int nn = mesh.elementNumNodes(e);
    const int* en = mesh.elementNodes(e);
    X.resize(nn, dim);
    ue.resize(nn, dim);
    for (int i = 0; i < nn; ++i)
      for (int c = 0; c < dim; ++c) {
        X(i, c) = mesh.coord(en[i])[c];
        ue(i, c) = ud[ovMap.getLocalElement(model.dof(en[i], c))];
      }
    ElementPostResult post;
    try {
      model.elementOf(e).postprocess(X, ue, post);
    } catch (const InadmissibleDeformation&) {
      // Output of a converged state never sees this; keep zeros if it does.
    }
    f(ElementOutput{e, en, nn, ue, post});
  }
}

void writeVtkStep(VtkWriter& writer, const Model& model, const Vector& u, int step, double time,
                  const Vector* velocity, const Vector* acceleration) {
  const Mesh& mesh = model.mesh();
  auto uov = model.toOverlap(u);
  // Nodal vectors besides the displacement (dynamics): name and overlap values.
  std::vector<std::pair<const char*, Teuchos::ArrayRCP<const double>>> extra;
  std::vector<Teuchos::RCP<Vector>> keep;
  for (const auto& [name, v] : {std::make_pair("velocity", velocity), std::make_pair("acceleration", acceleration)})
    if (v) {
      keep.push_back(model.toOverlap(*v));
      extra.emplace_back(name, keep.back()->getData());
    }
  const auto& ovMap = *model.overlapMap();
  const OutputSlots contactSlots = outputSlots(model);
  const auto& slotOf = contactSlots.slotOf;
  const bool contact = model.hasContact();
  std::map<int, VtkPiece> pieces;
  std::map<int, std::map<int, int>> pointIndex;  // subdomain -> (mesh node -> piece point)
  forEachLocalElementOutput(model, *uov, [&](const ElementOutput& o) {
    const int e = o.element;
    const int s = model.partition().elementSubdomain[e];
    VtkPiece& p = pieces[s];
    auto& index = pointIndex[s];
    if (p.pointData.empty()) {
      p.id = s;
      p.pointData = {{"displacement", 3, {}}};
      if (contact) p.pointData.insert(p.pointData.end(), {{"contact_gap", 1, {}}, {"contact_pressure", 1, {}}});
      for (const auto& x : extra) p.pointData.push_back({x.first, 3, {}});
      p.cellData = {{"cauchy_stress", 6, {}},
                    {"strain_energy_density", 1, {}},
                    {"body", 1, {}},
                    {"subdomain", 1, {}},
                    {"von_mises_stress", 1, {}}};
    }
    const int dim = mesh.dim();
    const int* en = o.nodes;
    // Points in the piece (each mesh node once), cells in VTK node order.
    const ReferenceCell& cell = referenceCell(mesh.elementType(e));
    for (int v = 0; v < o.numNodes; ++v) {
      const int i = cell.vtkOrder[v];
      auto [it, fresh] = index.emplace(en[i], p.numPoints());
      if (fresh) {
        p.points.insert(p.points.end(), {mesh.coord(en[i])[0], mesh.coord(en[i])[1], mesh.coord(en[i])[2]});
        auto& d = p.pointData[0].values;
        for (int c = 0; c < 3; ++c) d.push_back(c < dim ? o.ue(i, c) : 0.0);
        if (contact) {
          const ContactSlot* slot = slotOf[en[i]] >= 0 ? &contactSlots.slots[size_t(slotOf[en[i]])] : nullptr;
          p.pointData[1].values.push_back(slot && slot->paired() ? slot->gap : 0.0);
          p.pointData[2].values.push_back(slot ? slot->pressure() : 0.0);
        }
        const size_t first = contact ? 3 : 1;
        for (size_t k = 0; k < extra.size(); ++k)
          for (int c = 0; c < 3; ++c)
            p.pointData[first + k].values.push_back(
                c < dim ? extra[k].second[ovMap.getLocalElement(model.dof(en[i], c))] : 0.0);
      }
      p.connectivity.push_back(it->second);
    }
    p.offsets.push_back(static_cast<int>(p.connectivity.size()));
    p.types.push_back(static_cast<unsigned char>(cell.vtkType));
    const double* c = o.post.cauchy;  // xx, yy, zz, yz, xz, xy
    auto& st = p.cellData[0].values;
    st.insert(st.end(), {c[0], c[1], c[2], c[5], c[3], c[4]});
    p.cellData[1].values.push_back(o.post.energyDensity);
    p.cellData[2].values.push_back(mesh.elementBody(e));
    p.cellData[3].values.push_back(s);
    p.cellData[4].values.push_back(o.post.vonMises());
  });
  std::vector<VtkPiece> list;
  for (auto& kv : pieces) list.push_back(std::move(kv.second));
  writer.writeStep(step, time, list);
}

ExodusVariables exodusVariables(const Model& model, bool dynamics, std::vector<std::string> globals) {
  ExodusVariables v;
  const char* axes[] = {"x", "y", "z"};
  for (const char* field : {"displ", "vel", "acc"}) {
    if (std::string(field) != "displ" && !dynamics) continue;
    for (int c = 0; c < model.dim(); ++c) v.nodal.push_back(std::string(field) + "_" + axes[c]);
  }
  if (model.hasContact()) v.nodal.insert(v.nodal.end(), {"contact_gap", "contact_pressure", "contact_multiplier"});
  v.element = {"stress_xx", "stress_yy", "stress_zz", "stress_xy",
               "stress_yz", "stress_xz", "von_mises", "strain_energy_density"};
  v.global = std::move(globals);
  return v;
}

void writeExodusStep(ExodusWriter& writer, const Model& model, double time, const Vector& u,
                     const Vector* velocity, const Vector* acceleration, const std::vector<double>& globals) {
  const Mesh& mesh = model.mesh();
  const int dim = mesh.dim();
  const auto& ovMap = *model.overlapMap();
  auto uov = model.toOverlap(u);
  // The nodal fields after the displacement, in the order of exodusVariables().
  std::vector<Teuchos::ArrayRCP<const double>> fields;
  std::vector<Teuchos::RCP<Vector>> keep;
  for (const Vector* f : {velocity, acceleration})
    if (f) {
      keep.push_back(model.toOverlap(*f));
      fields.push_back(keep.back()->getData());
    }
  const OutputSlots contactSlots = outputSlots(model);
  const auto& slotOf = contactSlots.slotOf;
  const auto& slots = contactSlots.slots;
  ExodusStepValues values;
  values.global = globals;
  std::vector<char> seen(mesh.numNodes(), 0);
  forEachLocalElementOutput(model, *uov, [&](const ElementOutput& o) {
    for (int i = 0; i < o.numNodes; ++i) {
      const int n = o.nodes[i];
      if (seen[n]) continue;
      seen[n] = 1;
      values.nodes.push_back(n);
      for (int c = 0; c < dim; ++c) values.nodal.push_back(o.ue(i, c));
      for (const auto& f : fields)
        for (int c = 0; c < dim; ++c) values.nodal.push_back(f[ovMap.getLocalElement(model.dof(n, c))]);
      if (!slotOf.empty()) {
        const ContactSlot* s = slotOf[n] >= 0 ? &slots[size_t(slotOf[n])] : nullptr;
        values.nodal.push_back(s && s->paired() ? s->gap : 0.0);
        values.nodal.push_back(s ? s->pressure() : 0.0);
        values.nodal.push_back(s && s->active ? s->state.multiplier : 0.0);
      }
    }
    const double* s = o.post.cauchy;  // xx, yy, zz, yz, xz, xy
    values.elements.push_back(o.element);
    values.element.insert(values.element.end(), {s[0], s[1], s[2], s[5], s[3], s[4], o.post.vonMises(),
                                                 o.post.energyDensity});
  });
  writer.writeStep(time, values);
}

}  // namespace ddc
