-- The ashlar model library: each generator takes one option table and returns
-- a Structure with its supports set. Read them, copy them, make your own.
return {
  wall = require "ashlar.models.wall",
}
