#pragma once
// The feature cache of a dataset (docs/results.md): every view described once
// per parameter set by every block evaluate, train and consistency use — ISS
// keypoint functions, the same on random keypoints (u_*), Osada's D2/D3/A3, the
// length functions in RMS radii (s_*), the size block and the peers ESF, VFH and OUR-CVFH — kept in DATASET/.keyturn/features-<hash>.csv,
// the hash being of the feature specification (feature_spec.h). Shards (views
// i ≡ I−1 mod N for shard I of N) are written beside it and merged when all are present.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "keyturn/core/depth_image.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/dataset/dataset_views.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/keypoint_set.h"

namespace keyturn::learning {

// One view to describe: its file and its labels (a dataset's, keyturn/dataset/dataset_views.h).
using dataset::LabelledView;

// How a long describe run reports. view_done is called from the worker threads.
class DescribeProgress {
 public:
  virtual ~DescribeProgress() = default;
  virtual void begin(std::size_t views) = 0;
  virtual void viewDone() = 0;
  virtual void end() = 0;
  virtual void note(const std::string& line) = 0;     // what the cache did ("merged 4 feature shards")
  virtual void warning(const std::string& line) = 0;  // what went wrong and was recovered from
};

// What a block name says: a feature's PDF ("kpd2"), its twin on random keypoints ("u_kpd2"), its
// scale-normalised twin ("s_kpd2"; lengths only), the size block ("size"), a peer ("esf") or the
// keypoints themselves ("kpset", keypoint_set.h).
struct BlockName {
  enum Kind { Pdf, RandomTwin, ScaledTwin, Size, Peer, KeypointSet } kind = Pdf;
  Feature feature = Feature::KPD2;  // for Pdf and the twins
};
// Throws keyturn::Error for a name that is none of these.
BlockName parseBlockName(const std::string& name);

// Every block of the cache, in its column order.
const std::vector<std::string>& cacheBlocks();
// An empty table of these blocks (sizes from the options' bins) carrying the options' specification.
FeatureTable featureLayout(const std::vector<std::string>& blocks, const DescriptorOptions& options);
// DATASET/.keyturn/features-<hash>[.shard-I-of-N].csv (dataset::featureCacheFile), the hash being of
// the options' feature specification; shard counts from 0.
std::string featureCachePath(const std::string& dataset, const DescriptorOptions& options, int shard = 0,
                             int shards = 1);

// The camera a view came through, as the open-set scale tells cameras apart (open_set.h): the
// organized grid "WxH" of the cloud (the SR4000's 176x144, a Kinect-class camera's 640x480); "" for an
// unorganized cloud (a crop or a mesh scan: the pooled scale).
std::string cameraOf(const Cloud& cloud);

// One cloud described for the layout's blocks, as describeViews describes each file: a block that
// cannot be computed stays NaN and the row's problem says why (keypoints -1: no keypoint block).
// The row's camera is cameraOf(cloud).
FeatureRow describeCloud(const Cloud& cloud, const DescriptorOptions& options, const FeatureTable& layout);

// Describes views for the layout's blocks only, in parallel (jobs 0: all cores). A block that cannot
// be computed stays NaN and the row says why; an unreadable view has keypoints -1.
std::vector<FeatureRow> describeViews(const std::vector<LabelledView>& views, const DescriptorOptions& options,
                                      const FeatureTable& layout, int jobs, DescribeProgress* progress);

struct FeatureCache {
  std::string dataset;                // the cache lives in DATASET/.keyturn/
  std::vector<LabelledView> views;    // the dataset's views, manifest order
  DescriptorOptions options;          // the parameters (features are the cache's, whatever is set here)
  int jobs = 0;
  DescribeProgress* progress = nullptr;
  // loadOrDescribeCache saves the views described so far after a batch of checkpoint_views when
  // checkpoint_s have passed since the last save, so an interrupted describe (Ctrl-C, a killed job)
  // resumes where it stopped: the next run describes only the views the cache lacks.
  std::size_t checkpoint_views = 256;
  double checkpoint_s = 60;
  // The blocks the caller will read. A cache written before a block existed (the same parameters,
  // fewer blocks) gains the blocks of these it lacks, described alone for every view; a block no
  // caller has read yet stays out of it (describing it costs the keypoints of every view again).
  std::vector<std::string> needs;
};

// Describes the shard's views (i % shards == shard) into their shard file; returns its path.
std::string describeCacheShard(const FeatureCache& cache, int shard, int shards);
// The whole dataset's features: the cache if it is there, else merged shards if all are there,
// else described now and cached. Views no longer in the list are dropped, new ones described (and
// saved as they are, every cache.checkpoint_s). An older cache without some blocks is returned with
// the blocks it has, unless cache.needs names one it lacks or views are new (then it gains them).
FeatureTable loadOrDescribeCache(const FeatureCache& cache);

}  // namespace keyturn::learning
