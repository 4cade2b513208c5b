#pragma once
// Reading and writing point clouds through PCL: PCD (ascii, binary,
// binary_compressed) and PLY, and depth images. Organized PCDs stay organized. Every failure
// throws keyturn::Error naming the file and the problem.
#include <string>

#include "keyturn/core/cloud.h"
#include "keyturn/core/depth_image.h"

namespace pcl {
struct PCLPointCloud2;
}

namespace keyturn {

enum class PcdEncoding { Ascii, Binary, BinaryCompressed };

// Loads x, y, z and, when present, an amplitude (or intensity) and a confidence field, from a PCD
// or PLY; a .png is a 16-bit depth image read with `depth` (core/depth_image.h) as an organized cloud.
// Every view keyturn reads comes through here.
Cloud loadCloud(const std::string& path, const DepthImageOptions& depth = {});

// Writes fields x, y, z (+ amplitude, confidence when present). PLY when the
// path ends in .ply, PCD otherwise. Written to a temporary name and renamed.
void saveCloud(const std::string& path, const Cloud& cloud,
               PcdEncoding encoding = PcdEncoding::BinaryCompressed);

// x, y, z (any numeric type: PLY meshes often store doubles) plus amplitude or
// intensity and confidence from a PCL blob. `source` names it in errors.
Cloud cloudFromPclBlob(const std::string& source, const pcl::PCLPointCloud2& blob);

}  // namespace keyturn
