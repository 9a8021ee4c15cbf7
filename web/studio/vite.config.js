// The studio's front end: built into dist/, which `lsys studio` serves.
// Four pages: the editor (index.html), the drawing page (drawing.html),
// the guides page (guides.html) and the painting page (paint.html).
import { fileURLToPath } from "node:url";

const page = (name) => fileURLToPath(new URL(name, import.meta.url));

export default {
  base: "/",
  build: {
    outDir: "dist",
    emptyOutDir: true,
    chunkSizeWarningLimit: 1000,
    rollupOptions: { input: { main: page("index.html"), drawing: page("drawing.html"), guides: page("guides.html"), paint: page("paint.html") } },
  },
};
