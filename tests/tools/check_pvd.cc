// squeal-check-pvd FILE.pvd [--allow-empty] [FIELD ...]: opens a ParaView
// collection the way ParaView does, through VTK's XML readers: every
// DataSet it lists must exist and load (vtkXMLGenericDataObjectReader: .vtu,
// .pvtu and their pieces) without a VTK error, hold points, and carry every
// named point-data FIELD; a collection without a DataSet fails unless
// --allow-empty is given (Output/Mode shapes = none). Prints "FILE: N
// entries load" and exits 0, or names the first entry that does not and
// exits 1. The end-to-end checks run it on every .pvd a run writes.

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataSet.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLGenericDataObjectReader.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace
{
  bool vtk_error = false;

  void
  on_error(vtkObject *, unsigned long, void *, void *)
  {
    vtk_error = true;
  }

  int
  fail(const std::string &what)
  {
    std::cerr << "squeal-check-pvd: " << what << std::endl;
    return 1;
  }
} // namespace

int
main(int argc, char **argv)
{
  if (argc < 2)
    return fail("usage: squeal-check-pvd FILE.pvd [--allow-empty] [FIELD ...]");
  const std::filesystem::path pvd = argv[1];
  std::vector<std::string>    fields(argv + 2, argv + argc);
  const bool allow_empty = !fields.empty() && fields[0] == "--allow-empty";
  if (allow_empty)
    fields.erase(fields.begin());
  auto error = vtkSmartPointer<vtkCallbackCommand>::New();
  error->SetCallback(on_error);

  auto parser = vtkSmartPointer<vtkXMLDataParser>::New();
  parser->AddObserver(vtkCommand::ErrorEvent, error);
  parser->SetFileName(pvd.c_str());
  if (!std::filesystem::is_regular_file(pvd) || !parser->Parse() || vtk_error)
    return fail(pvd.string() + " is not a readable XML file");
  vtkXMLDataElement *collection =
    parser->GetRootElement()->FindNestedElementWithName("Collection");
  if (collection == nullptr)
    return fail(pvd.string() + " has no Collection");
  unsigned int n_entries = 0;
  for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i)
    {
      vtkXMLDataElement *entry = collection->GetNestedElement(i);
      if (std::string(entry->GetName()) != "DataSet")
        continue;
      const char *name = entry->GetAttribute("file");
      if (name == nullptr)
        return fail(pvd.string() + ": a DataSet without a file");
      const std::filesystem::path file = pvd.parent_path() / name;
      if (!std::filesystem::is_regular_file(file))
        return fail(pvd.string() + " names " + name + ", which does not exist");
      auto reader = vtkSmartPointer<vtkXMLGenericDataObjectReader>::New();
      reader->AddObserver(vtkCommand::ErrorEvent, error);
      reader->SetFileName(file.c_str());
      reader->Update();
      vtkDataSet *data = vtkDataSet::SafeDownCast(reader->GetOutput());
      if (vtk_error || data == nullptr)
        return fail(file.string() + " does not load through VTK's reader");
      if (data->GetNumberOfPoints() == 0)
        return fail(file.string() + " holds no points");
      for (const auto &field : fields)
        if (data->GetPointData()->GetArray(field.c_str()) == nullptr)
          return fail(file.string() + " has no point field " + field);
      ++n_entries;
    }
  if (n_entries == 0 && !allow_empty)
    return fail(pvd.string() + " lists no DataSet");
  std::cout << pvd.filename().string() << ": " << n_entries << " entries load"
            << std::endl;
  return 0;
}
