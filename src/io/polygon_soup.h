#pragma once
// What a reader returns: positions and polygon faces exactly as the file states them, with the source
// location of every element so that validation can name the file and line of each problem.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace quadcover {

struct PolygonSoup {
  std::string file;  ///< source path (for messages); empty for in-memory data

  /// #V by 3 vertex positions, as read (may contain NaN/inf: validation reports them).
  Eigen::MatrixX3d positions;
  /// Faces in compressed form: face f has corners face_vertices[face_offsets[f] .. face_offsets[f+1]),
  /// 0-based vertex indices as read (may be out of range: validation reports them).
  std::vector<std::int64_t> face_offsets{0};
  std::vector<std::int64_t> face_vertices;

  /// Optional texture coordinates (OBJ `vt` lines): #UV by 2 (u, v; a third `w` is ignored); empty if none.
  Eigen::MatrixX2d uv;
  /// Per-corner index into `uv`, same layout as face_vertices (0-based; -1 where a corner has no `vt`).
  /// Empty when the file has no `vt` references at all; otherwise face_uv.size() == face_vertices.size().
  std::vector<std::int64_t> face_uv;

  /// 1-based source line (OBJ/OFF/PLY ASCII/STL ASCII) or element number (binary formats) of each vertex and face;
  /// empty when the soup was built in memory.
  std::vector<long> vertex_lines;
  std::vector<long> face_lines;
  /// "line" for text formats, "element" for binary ones: how to read vertex_lines/face_lines.
  std::string location_unit = "line";
  /// For "element" locations: the file's element that locates a vertex ("vertex"; "facet" for STL, whose welded
  /// vertices are located by the first facet using them).
  std::string vertex_element = "vertex";

  /// How the file numbers vertices in its faces: 1 for OBJ, 0 for OFF, PLY and in-memory data (messages quote
  /// indices as the file writes them).
  int index_base = 0;

  std::size_t num_vertices() const { return static_cast<std::size_t>(positions.rows()); }  ///< \pre none
  std::size_t num_faces() const { return face_offsets.size() - 1; }  ///< \pre none
  /// \pre f < num_faces()
  std::size_t face_size(std::size_t f) const {
    return static_cast<std::size_t>(face_offsets[f + 1] - face_offsets[f]);
  }
  /// \pre f < num_faces()
  const std::int64_t* face_begin(std::size_t f) const { return face_vertices.data() + face_offsets[f]; }

  /// \pre [begin, begin + n) is readable.
  void add_face(const std::int64_t* begin, std::size_t n, long line) {
    face_vertices.insert(face_vertices.end(), begin, begin + n);
    face_offsets.push_back(static_cast<std::int64_t>(face_vertices.size()));
    face_lines.push_back(line);
  }

  bool has_uv() const { return !face_uv.empty(); }  ///< \pre none

  /// "file:line" (or "file, face element N" for binary formats) of face f / vertex v, for messages. \pre none
  std::string face_location(std::size_t f) const;
  std::string vertex_location(std::size_t v) const;  ///< \pre none

  /// A soup from plain triangle arrays (V #V by 3, F #F by 3, 0-based), e.g. from the Python module.
  /// \pre none (indices are checked by validate / build_mesh).
  static PolygonSoup from_triangles(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);
  /// A soup from a polygon mesh (quad meshes): V #V by 3, faces 0-based vertex indices per face (not checked here).
  /// \pre none
  static PolygonSoup from_polygons(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces);
};

/// Fans every polygon with more than three corners into triangles (corner 0 to each consecutive pair).
/// Used only when the user asks for it (`--triangulate`); face_lines and face_uv are kept for every piece.
/// \pre every face has at least 3 corners (validate() reports those that do not).
PolygonSoup triangulate_polygons(const PolygonSoup& soup);

}  // namespace quadcover
