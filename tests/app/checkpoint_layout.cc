// Where a checkpoint's datasets lie in the file, for the corruption test (checkpoint_corrupt.py):
// one line per dataset with data in the file, "OFFSET BYTES PATH" (its raw data's first byte
// and length; contiguous layout, as app/checkpoint.cc writes them), in the file's order.
//
// usage: checkpoint_layout FILE.h5
#include <hdf5.h>
#include <iostream>
#include <string>

namespace
{
herr_t print_dataset(hid_t root, const char* name, const H5O_info_t* info, void*)
{
  if (info->type != H5O_TYPE_DATASET)
    return 0;
  const hid_t set = H5Dopen2(root, name, H5P_DEFAULT);
  if (set < 0)
    return -1;
  const haddr_t offset = H5Dget_offset(set);
  const hsize_t bytes = H5Dget_storage_size(set);
  if (offset != HADDR_UNDEF && bytes > 0)
    std::cout << offset << ' ' << bytes << " /" << name << '\n';
  H5Dclose(set);
  return 0;
}
} // namespace

int main(int argc, char** argv)
{
  if (argc != 2)
  {
    std::cerr << "usage: checkpoint_layout FILE.h5\n";
    return 2;
  }
  const hid_t file = H5Fopen(argv[1], H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0)
    return 1;
  const herr_t visited = H5Ovisit(file, H5_INDEX_NAME, H5_ITER_INC, print_dataset, nullptr);
  H5Fclose(file);
  return visited < 0 ? 1 : 0;
}
