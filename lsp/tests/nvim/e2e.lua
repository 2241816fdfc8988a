-- Driven by run.sh: ROTLANG_LSP (server binary), ROTLANG_OUT (result JSON), ROTLANG_DIR
-- (scratch directory). Uses only APIs present in Neovim 0.7.2 (Debian's package).
local server = os.getenv("ROTLANG_LSP")
local out = os.getenv("ROTLANG_OUT")
local dir = os.getenv("ROTLANG_DIR")
local result = { steps = {} }

local function step(name) table.insert(result.steps, name) end

local function finish()
  vim.fn.writefile({ vim.fn.json_encode(result) }, out)
  vim.cmd("qa!")
end

local function run()
  local path = dir .. "/bad.rot"
  vim.fn.writefile({ "0, +30X5, +22.5/50%" }, path)
  vim.cmd("edit " .. path)
  local bufnr = vim.api.nvim_get_current_buf()

  local client_id = vim.lsp.start_client({
    name = "rotlang",
    cmd = { server },
    root_dir = dir,
    init_options = { rotlang = { layers = 100, layerHeight = 0.2 } },
  })
  result.client = client_id ~= nil
  if not client_id then return end
  vim.lsp.buf_attach_client(bufnr, client_id)
  step("attached")

  -- 1. The bad file gets its diagnostic.
  result.got_diagnostic = vim.wait(15000, function()
    return #vim.diagnostic.get(bufnr) > 0
  end, 50)
  local d = vim.diagnostic.get(bufnr)[1]
  if d then
    result.diagnostic = {
      message = d.message,
      lnum = d.lnum,
      col = d.col,
      end_col = d.end_col,
      severity = d.severity,
      code = d.code or (d.user_data and d.user_data.lsp and d.user_data.lsp.code),
    }
  end
  step("diagnosed")

  -- 2. Fix the text: the diagnostics clear.
  vim.api.nvim_buf_set_lines(bufnr, 0, -1, false, { "0, +30/5, +22.5/50%" })
  result.cleared = vim.wait(15000, function()
    return #vim.diagnostic.get(bufnr) == 0
  end, 50)
  step("fixed")

  -- 3. Hover on `+22.5/50%`.
  local params = {
    textDocument = { uri = vim.uri_from_bufnr(bufnr) },
    position = { line = 0, character = 13 },
  }
  local responses = vim.lsp.buf_request_sync(bufnr, "textDocument/hover", params, 15000)
  for _, r in pairs(responses or {}) do
    if r.result and r.result.contents then
      result.hover = r.result.contents.value or r.result.contents
    end
  end
  step("hovered")

  -- 4. Completion after `+30`, as the omnifunc does it: the start column is that of the
  -- keyword before the cursor (with the documented 'iskeyword', the whole instruction),
  -- and only words starting with the text from there are kept.
  vim.opt_local.iskeyword = "@,48-57,_,192-255,33-43,45-47,58,94,124,126"
  vim.api.nvim_buf_set_lines(bufnr, 0, -1, false, { "0, +30" })
  local line = "0, +30"
  local start = vim.fn.match(line, "\\k*$")
  local prefix = line:sub(start + 1)
  local cparams = {
    textDocument = { uri = vim.uri_from_bufnr(bufnr) },
    position = { line = 0, character = #line },
  }
  local cresponses = vim.lsp.buf_request_sync(bufnr, "textDocument/completion", cparams, 15000)
  result.completion_start = start
  result.completion_words = {}
  for _, r in pairs(cresponses or {}) do
    if r.result then
      for _, item in ipairs(vim.lsp.util.text_document_completion_list_to_complete_items(r.result, prefix)) do
        table.insert(result.completion_words, item.word)
      end
      local first = r.result[1] or (r.result.items or {})[1]
      if first and first.textEdit then
        result.completion_edit_start = first.textEdit.range.start.character
      end
    end
  end
  step("completed")

  vim.lsp.stop_client(client_id)
end

local ok, err = pcall(run)
result.ok = ok
if not ok then result.error = tostring(err) end
finish()
