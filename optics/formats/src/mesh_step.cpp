#include "airr/formats/mesh_step.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>
#include <utility>

#include <BRepMesh_IncrementalMesh.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Check.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <RWMesh_FaceIterator.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <StepData_StepModel.hxx>
#include <StepVisual_FillAreaStyle.hxx>
#include <StepVisual_FillAreaStyleColour.hxx>
#include <StepVisual_FillStyleSelect.hxx>
#include <StepVisual_HArray1OfFillStyleSelect.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <XCAFPrs_DocumentExplorer.hxx>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "step_references.hpp"

namespace airr {

namespace {

// The largest STEP file read, as any text file (a housing of millions of faces is far smaller).
constexpr std::uintmax_t max_step_bytes = max_text_file_bytes;

std::string label_name(const TDF_Label& label) {
  Handle(TDataStd_Name) name;
  if (!label.FindAttribute(TDataStd_Name::GetID(), name)) return {};
  return TCollection_AsciiString(name->Get()).ToCString();
}

// Appends the faces of one leaf of the product tree, placed by its location; a face's colour
// becomes a material, one per distinct colour.
void append_leaf(const XCAFPrs_DocumentNode& leaf, triangle_mesh& out,
                 std::map<std::array<float, 3>, std::uint32_t>& colours) {
  for (RWMesh_FaceIterator face(leaf.RefLabel, leaf.Location, true, leaf.Style); face.More(); face.Next()) {
    if (face.IsEmptyMesh()) continue;
    const std::uint32_t base = std::uint32_t(out.positions.size());
    for (int n = face.NodeLower(); n <= face.NodeUpper(); ++n) {
      const gp_Pnt p = face.NodeTransformed(n);
      out.positions.emplace_back(float(p.X()), float(p.Y()), float(p.Z()));
    }
    std::uint32_t material = 0;
    if (face.HasFaceColor()) {
      const Quantity_Color& c = face.FaceColor().GetRGB();  // linear RGB
      const std::array<float, 3> key{float(c.Red()), float(c.Green()), float(c.Blue())};
      const auto [it, added] = colours.try_emplace(key, std::uint32_t(out.materials.size()));
      if (added) {
        mesh_material m;
        m.name = "colour " + std::to_string(out.materials.size());
        m.base_color = {key[0], key[1], key[2]};
        m.metallic = 0.0f;
        out.materials.push_back(m);
      }
      material = it->second;
    } else {
      material = std::uint32_t(-1);
    }
    for (int t = face.ElemLower(); t <= face.ElemUpper(); ++t) {
      // Oriented: counter-clockwise seen from outside the solid, whatever the face's orientation.
      const Poly_Triangle tri = face.TriangleOriented(t);
      int a, b, c;
      tri.Get(a, b, c);
      for (int k : {a, b, c}) out.indices.push_back(base + std::uint32_t(k - face.NodeLower()));
      out.triangle_materials.push_back(material);
    }
  }
}

// Open CASCADE's transfer follows references without checking they are there: a line the parser
// could not read (the entities naming it left with nothing), an entity of the wrong type or a
// fill colour that names none would crash it (fuzzing found each), so such a file is refused first.
void check_entities(STEPCAFControl_Reader& reader, const std::string& path) {
  const Handle(Interface_InterfaceModel) model = reader.Reader().Model();
  if (model.IsNull()) return;
  const auto refuse = [&](int i, const char* what) {
    throw input_error(path + ": entity " + std::to_string(i) + ", a fill style, " + what);
  };
  // Syntax errors and references to entities that are not there.
  const Handle(Interface_Check) global = model->GlobalCheck();
  if (!global.IsNull() && global->NbFails() > 0) throw input_error(path + ": " + one_line(global->CFail(1)));
  const Handle(StepData_StepModel) step = reader.Reader().StepModel();
  for (int i = 1; i <= model->NbEntities() && !step.IsNull(); ++i) {
    if (!model->IsErrorEntity(i)) continue;
    const Handle(Interface_Check)& check = model->Check(i, true);
    const std::string why = !check.IsNull() && check->NbFails() > 0 ? one_line(check->CFail(1)) : "unreadable";
    throw input_error(path + ": entity #" + std::to_string(step->IdentLabel(model->Value(i))) + ": " + why);
  }
  for (int i = 1; i <= model->NbEntities(); ++i) {
    const auto colour = Handle(StepVisual_FillAreaStyleColour)::DownCast(model->Value(i));
    if (!colour.IsNull() && colour->FillColour().IsNull()) refuse(i, "names no colour");
    const auto style = Handle(StepVisual_FillAreaStyle)::DownCast(model->Value(i));
    if (style.IsNull()) continue;
    if (style->FillStyles().IsNull()) refuse(i, "has no fills");
    for (int k = 1; k <= style->NbFillStyles(); ++k) {
      const Handle(StepVisual_FillAreaStyleColour) fill = style->FillStylesValue(k).FillAreaStyleColour();
      if (fill.IsNull() || fill->FillColour().IsNull()) refuse(i, "has a fill without a colour");
    }
  }
}

// The reader's document, closed when done: the application keeps every document it made, with
// its shapes and their tessellation, until it is closed.
struct step_document {
  Handle(TDocStd_Document) doc;
  step_document() { XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc); }
  ~step_document() {
    if (!doc.IsNull() && doc->IsOpened()) XCAFApp_Application::GetApplication()->Close(doc);
  }
  step_document(const step_document&) = delete;
  step_document& operator=(const step_document&) = delete;
};

triangle_mesh read_step(const std::string& path, const std::string& node, double tolerance_mm) {
  step_document document;
  Handle(TDocStd_Document)& doc = document.doc;
  STEPCAFControl_Reader reader;
  reader.SetColorMode(true);
  reader.SetNameMode(true);
  std::string text = read_text_file(path);
  if (const std::string fault = step_reference_fault(text); !fault.empty()) throw input_error(path + ": " + fault);
  {
    // The text scanned above is the text read (the file is not opened twice), let go once parsed.
    std::istringstream stream(std::move(text));
    if (reader.ChangeReader().ReadStream(path.c_str(), stream) != IFSelect_RetDone)
      throw input_error(path + ": not a readable STEP file");
  }
  check_entities(reader, path);
  if (!reader.Transfer(doc)) throw input_error(path + ": its shapes could not be read");

  const Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  TDF_LabelSequence roots;
  shapes->GetFreeShapes(roots);
  for (int i = 1; i <= roots.Length(); ++i) {
    // Tessellated in place: the document's shapes share their faces with the tree's leaves.
    BRepMesh_IncrementalMesh(XCAFDoc_ShapeTool::GetShape(roots.Value(i)), tolerance_mm, false, 0.5, false);
  }

  triangle_mesh out;
  out.name = node.empty() ? std::filesystem::path(path).stem().string() : node;
  std::map<std::array<float, 3>, std::uint32_t> colours;
  bool found = node.empty();
  int inside_depth = node.empty() ? 0 : -1;  // the depth of the named product while within it
  for (XCAFPrs_DocumentExplorer e(doc, XCAFPrs_DocumentExplorerFlags_None); e.More(); e.Next()) {
    const XCAFPrs_DocumentNode& n = e.Current();
    const int depth = e.CurrentDepth();
    if (!node.empty()) {
      if (inside_depth >= 0 && depth <= inside_depth) inside_depth = -1;
      if (inside_depth < 0 && (label_name(n.RefLabel) == node || label_name(n.Label) == node)) {
        inside_depth = depth;
        found = true;
      }
      if (inside_depth < 0) continue;
    }
    if (!n.IsAssembly) append_leaf(n, out, colours);
  }
  if (!found) throw input_error(path + ": no product named " + node);
  if (out.indices.empty()) {
    throw input_error(path + (node.empty() ? std::string() : ": product " + node) + ": no surfaces to tessellate");
  }
  // Faces without a colour keep glTF's default material, as a mesh without materials would.
  if (!out.materials.empty()) {
    const auto none = std::uint32_t(out.materials.size());
    bool any_plain = false;
    for (std::uint32_t& m : out.triangle_materials) {
      if (m == std::uint32_t(-1)) m = none, any_plain = true;
    }
    if (any_plain) out.materials.push_back(mesh_material{"no colour"});
  } else {
    out.triangle_materials.clear();
  }
  return out;
}

}  // namespace

bool is_step_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".step" || ext == ".stp";
}

triangle_mesh load_step_mesh(const std::string& path, const std::string& node, double tolerance_mm) {
  if (!(tolerance_mm >= 1e-4 && tolerance_mm <= 100)) {
    throw input_error(path + ": tessellation tolerance " + number_text(tolerance_mm) + " mm is outside 0.0001-100 mm");
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw input_error(path + ": file not found");
  if (std::filesystem::file_size(path, ec) > max_step_bytes) {
    throw input_error(path + ": larger than the limit of " + std::to_string(max_step_bytes >> 20) +
                      " MB for STEP files");
  }
  // Open CASCADE's STEP translator keeps its settings in globals: one file at a time.
  static std::mutex one_at_a_time;
  const std::lock_guard lock(one_at_a_time);
  static const bool quiet = [] {
    Message::DefaultMessenger()->ChangePrinters().Clear();  // its progress lines are not ours to print
    return true;
  }();
  (void)quiet;
  try {
    return read_step(path, node, tolerance_mm);
  } catch (const Standard_Failure& e) {
    throw input_error(path + ": not a readable STEP file (" + one_line(e.GetMessageString()) + ")");
  }
}

}  // namespace airr
