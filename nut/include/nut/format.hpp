// nut/format.hpp — the HNI (Hierarchical NUT Image) format constants, versions 1 to 3.
//
// The full byte-level specification is docs/FORMAT.md; this header is its single source in code
// (the GLSL constants are generated from it). In short: an HNI is an RGBA8 image. The upper-left
// 256x256 pixels are the *metadata region*, addressed with 8-bit (u, v) pairs; it holds the file
// record at (0,0), the block table, every block header, every metadata array (with its exact row)
// and every redirection record. Data components, the material array and the texture-info array may
// lie anywhere in the image and are addressed with 12-bit (u, v) pairs packed into 24 bits.
// Every address is relative to the HNI's own origin, so an HNI can sit anywhere in an atlas.
//
//   file record    (0,0) 6 px   magic "NUT", version, root, counts, array origins
//   block header   12 px x 1    visual summary S, sizes D, cell counts N, metadata sizes M, addresses
//   metadata item  M px x 2     row 0: (i, f, j_left, j_right) per metadata pixel; row 1: exact row
//   redirection    4 px x 1     offset O (3 x s24 mm), tiling flags, rotation, LOD footprint, target header
//   data component nx*nz x ny   one pixel per cell: (material lo, material hi, texture, g)
//   material       2 px         (r, g, b, opacity), (reflectance, 0, 0, 0)
//   texture info   3 px         offset To (3 x s24 mm), texture id (u16)
//   plane cell     4 or 7 px    material, texture, combination; per plane: normal (2 x u24), offset
//
// Lengths are integers of millimetres: unsigned 24-bit for sizes and boundary positions (up to
// 16777.215 m), signed 24-bit for offsets. Multi-byte fields are little-endian across R, G, B.
#pragma once

#include <cstdint>

namespace nut::format {

inline constexpr std::uint8_t kMagic[3] = {'N', 'U', 'T'};
// A writer writes the lowest version that holds its content: version 2 only when some redirection
// record carries a level-of-detail footprint. A reader reads both.
inline constexpr std::uint8_t kVersion = 1;
inline constexpr std::uint8_t kVersionLod = 2;
// Version 3: some cell is a plane cell (g = kCellPlane); it holds version 2's records as well.
inline constexpr std::uint8_t kVersionPlanes = 3;

// Image limits. The width search of compile stops at kMaxSearchWidth unless one item is wider;
// no HNI may exceed kMaxImageSize in either dimension (it must fit a viewer atlas page).
inline constexpr int kMetadataRegion = 256;
inline constexpr int kMaxSearchWidth = 256;
inline constexpr int kMaxImageSize = 4096;

// Per-axis limits of a block: W cells indexed by M = W + w metadata pixels, W <= M <= 256.
inline constexpr int kMaxCellsPerAxis = 256;
inline constexpr int kMaxMetadataPixels = 256;
// f is an 8-bit fraction of a metadata pixel: the heuristic error is at most D / (512 M).
inline constexpr int kFractionSteps = 256;

// Units: 1 unit = 1 mm.
inline constexpr double kMetresPerUnit = 0.001;
inline constexpr std::int32_t kMaxLengthUnits = (1 << 24) - 1;   // u24
inline constexpr std::int32_t kMinOffsetUnits = -(1 << 23);      // s24
inline constexpr std::int32_t kMaxOffsetUnits = (1 << 23) - 1;

// Record sizes in pixels.
inline constexpr int kFileRecordPixels = 6;
inline constexpr int kHeaderPixels = 12;
inline constexpr int kRedirectionPixels = 4;
inline constexpr int kMaterialPixels = 2;
inline constexpr int kTextureInfoPixels = 3;
inline constexpr int kBlockTableEntriesPerPixel = 2;
// Arrays that may hold many entries are laid out as rectangles at most this many entries wide.
inline constexpr int kMaterialsPerRow = 128;
inline constexpr int kTextureInfosPerRow = 85;
inline constexpr int kBlockTablePixelsPerRow = 128;
inline constexpr int kRedirectionsPerItem = 16;

// File record pixel indices (x coordinate at y = 0).
inline constexpr int kFileMagic = 0;         // 'N' 'U' 'T' version
inline constexpr int kFileRoot = 1;          // root header u, v; block count u16
inline constexpr int kFileMaterials = 2;     // material array origin u12v12; entries per row
inline constexpr int kFileCounts = 3;        // material count u16; redirection count u16
inline constexpr int kFileTextures = 4;      // texture-info origin u12v12; entries per row
inline constexpr int kFileBlockTable = 5;    // texture-info count; block table u, v; flags

// Block header pixel indices.
inline constexpr int kHeaderSummary = 0;     // 6 px: S+x, S-x, S+y, S-y, S+z, S-z (r, g, b, coverage)
inline constexpr int kHeaderSize = 6;        // 3 px: D axis u24 in R,G,B; A = n_axis - 1
inline constexpr int kHeaderMetaSizes = 9;   // M_x - 1, M_y - 1, M_z - 1, C byte 0
inline constexpr int kHeaderMetaXY = 10;     // metadata item of x (u, v), of y (u, v)
inline constexpr int kHeaderMetaZ = 11;      // metadata item of z (u, v), C bytes 1, 2

// Cell descriptor g (alpha of a data pixel).
inline constexpr std::uint8_t kCellEmpty = 0;
inline constexpr std::uint8_t kCellRedirection = 1;
inline constexpr std::uint8_t kCellFirstSolid = 2;
inline constexpr int kSolidCount = 69;
inline constexpr std::uint8_t kCellLastSolid = kCellFirstSolid + kSolidCount - 1;  // 70
// Version 3: a plane cell; R, G, B of the data pixel are the 12-bit address of its record.
inline constexpr std::uint8_t kCellPlane = kCellLastSolid + 1;  // 71

// Plane cell record: one pixel (material u16, texture, combination byte), then three pixels per
// plane: the normal's octahedral coordinates e_x, e_y (u24 each) and the offset (s32, in
// 1/kPlaneOffsetStepsPerUnit mm). An octahedral coordinate u in 1..kOctahedralMax stands for
// (u - kOctahedralCentre) / kOctahedralSteps, so 0 and +-1 are exact.
inline constexpr int kPlaneRecordHeadPixels = 1;
inline constexpr int kPixelsPerPlane = 3;
inline constexpr std::uint32_t kOctahedralCentre = 1u << 23;
inline constexpr std::uint32_t kOctahedralSteps = (1u << 23) - 1;
inline constexpr std::uint32_t kOctahedralMax = (1u << 24) - 1;
inline constexpr int kPlaneOffsetStepsPerUnit = 64;

// Redirection record: A of pixel 0 holds the tiling flags, A of pixel 1 the cube rotation, A of
// pixel 2 (version 2) the target's level-of-detail footprint code c: 0 = none, else the summary may
// stand in where one pixel spans more than 2^((c - kLodCodeOneMetre) / kLodCodesPerOctave) metres.
inline constexpr std::uint8_t kWrapX = 1, kWrapY = 2, kWrapZ = 4;
inline constexpr int kRedirectionLodPixel = 2;
inline constexpr int kLodCodeOneMetre = 128;
inline constexpr int kLodCodesPerOctave = 16;
inline constexpr int kCubeRotationCount = 24;
// The free yaw angle about the sub-block's y axis is a u16 fraction of a full turn.
inline constexpr int kYawSteps = 65536;

// Texture index in a data pixel: 0 = none, n = texture-info entry n - 1.
inline constexpr int kMaxTextureInfos = 255;
// Material indices are u16, and so is the file record's material count.
inline constexpr int kMaxMaterials = 65535;

}  // namespace nut::format
